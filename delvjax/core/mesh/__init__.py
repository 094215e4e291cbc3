"""Triangle-mesh worlds (docs/mesh.md): a mesh of coloured triangles over a ground plane, and panoramas of
it cast ray by ray as one array program at any pose (`render.py`)."""
