"""Triangle-mesh worlds (docs/mesh.md): the field's ant world read from the user's files (`read_mesh`,
`read_route`), a seeded habitat of our own (`habitat`), their panoramas at any pose (`panoramas`), a world with
its route for the familiarity experiments (`mesh_site`, `file_site`) and its image databases in BoB's layout
(`render_mesh_database`)."""

from ._database import render_mesh_database as render_mesh_database
from ._files import read_mesh as read_mesh
from ._files import read_route as read_route
from ._habitat import habitat as habitat
from ._site import MeshSite as MeshSite
from ._site import file_site as file_site
from ._site import mesh_site as mesh_site
from ._world import ANT_EYE as ANT_EYE
from ._world import Eye as Eye
from ._world import mesh_world as mesh_world
from ._world import panoramas as panoramas
