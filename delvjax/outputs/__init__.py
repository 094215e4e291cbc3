"""What a run leaves on disk: files written atomically, one table schema per result type, the
compilation cache (docs/model.md §7)."""

from ._files import write_csv as write_csv
from ._files import write_figure as write_figure
from ._files import write_json as write_json
from ._tables import catchment_columns as catchment_columns
from ._tables import vector_map_columns as vector_map_columns
from ._tables import to_dataframe as to_dataframe
