"""Method configuration and noise models (docs/model.md §2.5, §3, §4; defaults are SPEC's).

`Config` is an equinox module: continuous parameters are pytree leaves (they can be
traced, vmapped in a sweep, or differentiated), discrete ones are static fields
(changing them recompiles).
"""

from __future__ import annotations

import equinox as eqx

BACKGROUNDS = ("distant", "walls", "none")
CHANNELS = ("mask", "gray")


class Noise(eqx.Module):
    """Noise standard deviations (docs/model.md §2.5). Angles in radians, step factors unitless.

    bearing:        per-blob bearing noise.
    step:           unit-move length factor `1 + N(0, step)` (the agent believes it moved d).
    turn:           true turn `psi ~ N(0, turn)` during the unit move.
    turn_odometry:  error of the odometry's report of that turn, `psi_hat = psi + N(0, .)`.
    compass:        error of the compass reading of `h - alpha_r`.
    motion_heading: rollouts only: error of the executed heading of each step.
    motion_step:    rollouts only: step length factor `1 + N(0, .)` of each step.
    """

    bearing: float = 0.0
    step: float = 0.0
    turn: float = 0.0
    turn_odometry: float = 0.0
    compass: float = 0.0
    motion_heading: float = 0.0
    motion_step: float = 0.0


class Config(eqx.Module):
    """Everything a homing method and its sensing need besides the scene.

    d:         unit-movement step, cm (docs/model.md §3.1, default 50).
    scale:     quantization scale `a`, cm (docs/model.md §3.2, default 1000).
    r_max:     cap of estimated distances, cm (docs/model.md §3.1, default 2000).
    alpha_r:   reference heading at home, radians (docs/model.md §1, default 0).
    mfdid_blur_deg: Gaussian low-pass of MFDID's images, degrees (0 = none; §4.5).
    noise:     `Noise` (all zero by default).
    levels:    quantization levels Q (0, or None when constructing, = continuous distances);
               a traced leaf, so a sweep can vmap over Q and every Q shares one program.
    n_pix:     ring image width in pixels (360).
    n_heading: heading hypotheses of DELV's matching (360).
    n_alpha, n_psi, n_rho, rho_min, rho_max: warping hypotheses (docs/model.md §4.3: 72 movement
               directions, 72 rotations, 15 rho = d/r values 0.10..0.80).
    background: docs/model.md §2.3 setting, stored as an index into BACKGROUNDS (0 distant, 1 walls,
               2 none; a name is converted): a traced leaf, so every setting shares one program.
    channel:   docs/model.md §2.2.
    """

    d: float = 50.0
    scale: float = 1000.0
    r_max: float = 2000.0
    alpha_r: float = 0.0
    mfdid_blur_deg: float = 0.0
    noise: Noise = Noise()
    levels: int = eqx.field(default=0, converter=lambda q: 0 if q is None else q)
    n_pix: int = eqx.field(static=True, default=360)
    n_heading: int = eqx.field(static=True, default=360)
    n_alpha: int = eqx.field(static=True, default=72)
    n_psi: int = eqx.field(static=True, default=72)
    n_rho: int = eqx.field(static=True, default=15)
    rho_min: float = eqx.field(static=True, default=0.10)
    rho_max: float = eqx.field(static=True, default=0.80)
    background: int = eqx.field(default=0, converter=lambda b: BACKGROUNDS.index(b) if isinstance(b, str) else b)
    channel: str = eqx.field(static=True, default="mask")
