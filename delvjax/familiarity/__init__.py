"""Route following by visual familiarity (docs/familiarity.md): perfect memory, InfoMax and a mushroom
body trained on a route, their rotational image difference functions, heading fields, route-following
trials and catchment areas."""

from ._gradients import unfamiliarity_grad as unfamiliarity_grad
from ._models import MODELS as MODELS
from ._models import make_model as make_model
from ._models import ridf as ridf
from ._models import train_model as train_model
from ._routes import RouteImages as RouteImages
from ._routes import plan_route as plan_route
from ._routes import route_from_database as route_from_database
from ._routes import route_in_world as route_in_world
from ._run import FamiliarityResult as FamiliarityResult
from ._run import database_experiments as database_experiments
from ._run import route_experiments as route_experiments
