"""`python -m delvjax.cli`: the same as the `delvjax` command."""

from ._entry import main

raise SystemExit(main())
