"""Image databases (docs/images.md): render a colour world into a database, read and write the
BoB layout on disk, evaluate homing methods on a database."""

from ._evaluate import database_catchment as database_catchment
from ._evaluate import database_rollouts as database_rollouts
from ._evaluate import database_success_rate as database_success_rate
from ._evaluate import database_vector_map as database_vector_map
from ._import import import_database as import_database
from ._in_memory import render_in_memory as render_in_memory
from ._in_memory import rendered_database as rendered_database
from ._load import DatabaseWarning as DatabaseWarning
from ._load import LoadedDatabase as LoadedDatabase
from ._load import load_database as load_database
from ._navipy import from_navipy as from_navipy
from ._navipy import to_navipy as to_navipy
from ._render import ImageSettings as ImageSettings
from ._render import render_database as render_database
from ._worlds import image_world as image_world
