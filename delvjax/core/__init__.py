"""The model as array programs (docs/architecture.md): methods as equinox modules, the sensor and its
noise, sensing, distance estimation, the per-point kernel, vector maps, rollouts, metrics. This
__init__ re-exports the array API: the modules, the sensor, the scene, the maps and the rollouts.

The core never reads files, prints, parses options or looks a method up by name; the rest of
`delvjax` (the edge) does that and depends on the core, never the reverse.
"""

from . import analysis as analysis
from . import maps as maps
from . import metrics as metrics
from . import rollouts as rollouts
from . import sensitivity as sensitivity
from .errors import InputError as InputError
from .maps import VectorMap as VectorMap
from .maps import grid_points as grid_points
from .maps import vector_map as vector_map
from .methods import ACV as ACV
from .methods import ALV as ALV
from .methods import DELV as DELV
from .methods import MFDID as MFDID
from .methods import CartwrightCollett as CartwrightCollett
from .methods import Compass as Compass
from .methods import DELVGap as DELVGap
from .methods import DELVRefined as DELVRefined
from .methods import HomingMethod as HomingMethod
from .methods import MethodSet as MethodSet
from .methods import VisualCompass as VisualCompass
from .methods import Warping as Warping
from .metrics import error_curve as error_curve
from .metrics import error_point_rates as error_point_rates
from .metrics import summarize_map as summarize_map
from .rollouts import catchment_area as catchment_area
from .rollouts import success_rate_trials as success_rate_trials
from .rollouts import trajectory_trials as trajectory_trials
from .scene import Env as Env
from .sensing import Snapshot as Snapshot
from .sensing import UnitMove as UnitMove
from .sensor import Noise as Noise
from .sensor import Sensor as Sensor
