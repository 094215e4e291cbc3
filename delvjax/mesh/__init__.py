"""Triangle-mesh worlds (docs/mesh.md): the field's ant world read from the user's files (`read_mesh`,
`read_route`), a seeded habitat of our own (`habitat`), and their panoramas at any pose (`panoramas`)."""

from ._files import read_mesh as read_mesh
from ._files import read_route as read_route
from ._habitat import habitat as habitat
from ._world import ANT_EYE as ANT_EYE
from ._world import Eye as Eye
from ._world import mesh_world as mesh_world
from ._world import panoramas as panoramas
