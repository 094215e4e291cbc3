"""User options: method names (the registry), validated settings, run-size limits
(docs/model.md §3-4, §7)."""

from ._limits import MAX_POINTS as MAX_POINTS
from ._registry import DESCRIPTIONS as DESCRIPTIONS
from ._registry import METHODS as METHODS
from ._registry import get_method as get_method
from ._registry import method_set as method_set
from ._registry import public_classes as public_classes
from ._registry import register as register
from ._registry import unregister as unregister
from ._schema import Option as Option
from ._schema import all_options as all_options
from ._setup import make_sensor as make_sensor
from ._setup import make_setup as make_setup
