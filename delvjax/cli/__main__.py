"""`python -m delvjax.cli`: the same as the `delvjax` command."""

from ._main import main

raise SystemExit(main())
