"""The agent's senses and their noise (docs/model.md §2.2-2.5, §3.1): one `Sensor`, one `Noise`.

Both are equinox modules: continuous settings are pytree leaves (traced, vmapped in a sweep,
differentiated), shapes and choices are static fields (changing them recompiles). The
defaults written here are the model's (docs/model.md §8); the CLI and the API read them.
Every noise draw of the model is made by a `Noise` method, so maps, rollouts and
sensitivity studies sample the noise model the same way.
"""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from .settings import radians, setting
from .types import Real

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

    bearing: Real = setting(
        0.0,
        check="non_negative",
        unit="deg",
        to_field=radians,
        option="bearing_noise_deg",
        help="error of every blob bearing, in every snapshot",
    )
    step: Real = setting(
        0.0,
        check="non_negative",
        unit="fraction of d",
        option="step_noise",
        help="error of the unit move's length, d * (1 + N(0, s)); the agent believes it moved d",
    )
    turn: Real = setting(
        0.0,
        check="non_negative",
        unit="deg",
        to_field=radians,
        option="turn_noise_deg",
        help="true body turn during the unit move; the end view is rotated by it",
    )
    turn_odometry: Real = setting(
        0.0,
        check="non_negative",
        unit="deg",
        to_field=radians,
        option="odometry_turn_noise_deg",
        help="error of the odometry's report of that turn",
    )
    compass: Real = setting(
        0.0,
        check="non_negative",
        unit="deg",
        to_field=radians,
        option="compass_noise_deg",
        help="error of every compass reading (compass methods only)",
    )
    motion_heading: Real = setting(
        0.0,
        check="non_negative",
        unit="deg",
        to_field=radians,
        option="motion_heading_noise_deg",
        help="rollouts only: error of the executed heading of every step",
    )
    motion_step: Real = setting(
        0.0,
        check="non_negative",
        unit="fraction of d",
        option="motion_step_noise",
        help="rollouts only: error of every step's length, d * (1 + N(0, s))",
    )

    def unit_move(self, key: Array, d: Real) -> tuple[Array, Array, Array, Array]:
        """Draws of an imagined unit movement (vector maps, the home record; docs/model.md §2.5):
        (true length, true turn psi, odometry's psi_hat, key of the observation)."""
        k_step, k_turn, k_odo, k_obs = jax.random.split(key, 4)
        length = d * (1.0 + self.step * jax.random.normal(k_step, dtype=jnp.float32))
        psi = self.turn * jax.random.normal(k_turn, dtype=jnp.float32)
        return length, psi, psi + self.turn_odometry * jax.random.normal(k_odo, dtype=jnp.float32), k_obs

    def rollout_move(self, key: Array, d: Real) -> tuple[Array, Array, Array, Array, Array]:
        """Draws of one rollout move (docs/model.md §5): (heading error, true length, psi, psi_hat,
        key of the observation); the length carries both the unit-move and the motion step noise."""
        k_draw, k_obs = jax.random.split(key)
        z_heading, z_step, z_motion_step, z_turn, z_odometry = jax.random.normal(k_draw, (5,), dtype=jnp.float32)
        length = d * (1.0 + self.step * z_step) * (1.0 + self.motion_step * z_motion_step)
        psi = self.turn * z_turn
        return self.motion_heading * z_heading, length, psi, psi + self.turn_odometry * z_odometry, k_obs

    def observation_keys(self, key: Array) -> tuple[Array, Array, Array]:
        """(compass, start snapshot, end snapshot) keys of one observed move."""
        k_compass, k_start, k_end = jax.random.split(key, 3)
        return k_compass, k_start, k_end

    def compass_error(self, key: Array) -> Array:
        """Error of one compass reading, rad."""
        return self.compass * jax.random.normal(key, dtype=jnp.float32)

    def bearing_errors(self, key: Array, shape: tuple[int, ...]) -> Array:
        """Per-blob bearing errors, rad."""
        return self.bearing * jax.random.normal(key, shape, dtype=jnp.float32)


class Sensor(eqx.Module):
    """How the agent sees and measures (docs/model.md §2-3.1).

    d:          unit-movement step, cm (§3.1; also the step of a rollout, §5).
    alpha_r:    reference heading at home, rad (§1).
    noise:      `Noise` (all zero by default).
    background: §2.3 setting as an index into BACKGROUNDS (0 distant, 1 walls, 2 none; a name
                is converted): a traced leaf, so every setting shares one program.
    n_pix:      ring image width in pixels (§2.2).
    channel:    image channel read by the image methods (warping, MFDID; §2.2): mask or gray.
    panorama:   None, or a renderer of the scene's panoramas (`core.images.ScenePanorama`, called as
                `panorama(env, visible, pos, heading)`) for the methods that read them (MinWarping;
                docs/images.md §10); the edge sets it (`options.make_setup`).
    """

    d: Real = setting(50.0, check="positive", unit="cm", help="unit-movement step")
    alpha_r: Real = setting(
        0.0, check="angle_deg", unit="deg", to_field=radians, option="alpha_r_deg", help="reference heading at home"
    )
    noise: Noise = Noise()
    background: Real = setting(
        0,
        converter=lambda b: BACKGROUNDS.index(b) if isinstance(b, str) else b,
        check="choice",
        choices=BACKGROUNDS,
        shown_default=BACKGROUNDS[0],
        help="what the agent sees beyond the landmarks (docs/model.md §2.3)",
    )
    n_pix: int = setting(360, static=True, check="positive_int", limit=36_000, help="ring image width in pixels")
    channel: str = setting(
        "mask",
        static=True,
        check="choice",
        choices=CHANNELS,
        help="image channel of the image methods (warping, mfdid)",
    )
    panorama: eqx.Module | None = None
