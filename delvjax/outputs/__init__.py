"""What a run leaves on disk: files written atomically, the compilation cache (docs/model.md §7). The
table schema of each result type lives with the results (`delvjax.core.tables`)."""

from ._files import write_csv as write_csv
from ._files import write_figure as write_figure
from ._files import write_json as write_json
