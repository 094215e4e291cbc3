"""The differentiable evaluation path (docs/differentiable.md): analytic views with a soft
visibility (`sensing`), softmin versions of DELV, ALV and ACV (`methods`), and the homing field
and its loss as smooth functions of the scene, the agent and the noise (`loss`)."""
