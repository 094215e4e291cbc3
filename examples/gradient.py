"""How the homing loss of DELV responds to the landmarks and to bearing noise: `jax.grad` through a
whole vector map (docs/differentiable.md).

    python examples/gradient.py

The homing loss is the mean of 1 - cos(angular error) over the grid: 0 is perfect, lower is better.
Its soft version (temperature `tau`) is a pure JAX function of the environment and the settings.
"""

import equinox as eqx
import jax
import jax.numpy as jnp

import delvjax

env = delvjax.load_env("env1")


def loss_of(landmarks: jax.Array, noise_deg: jax.Array) -> jax.Array:
    moved = eqx.tree_at(lambda e: e.landmarks, env, landmarks)  # the same Env with traced landmarks
    return delvjax.homing_loss(moved, "delv", spacing=100.0, bearing_noise_deg=noise_deg, tau=0.01)


landmarks = jnp.asarray(env.landmarks)  # (N, 3): x, y, r in cm
value = loss_of(landmarks, 1.0)
d_landmarks, d_noise = jax.grad(loss_of, argnums=(0, 1))(landmarks, jnp.float32(1.0))
print(f"loss {float(value):.4f} (lower is better); d loss / d bearing noise = {float(d_noise):+.4f} per degree")
for i, (g, lm) in enumerate(zip(d_landmarks, landmarks)):
    x, y = float(lm[0]), float(lm[1])
    print(
        f"landmark {i} at ({x:.0f}, {y:.0f}) cm: d loss / d(x, y) = ({float(g[0]) * 100:+.4f}, {float(g[1]) * 100:+.4f}) per m"
    )
# the same gradient and more in one call (reverse mode over every parameter at once); smoothing_cm=None asks
# for the gradient at the point, as jax.grad gives it
kw = dict(spacing=100.0, bearing_noise_deg=1.0, tau=0.01)
value2, grads = delvjax.homing_loss_grad("env1", "delv", smoothing_cm=None, **kw)
print("homing_loss_grad gives:", ", ".join(sorted(grads)))
assert abs(float(value2) - float(value)) < 1e-5
assert jnp.allclose(grads["landmarks"], d_landmarks, rtol=1e-3, atol=1e-7)
# what a researcher asks: the sensitivity at a stated scale, here the loss smoothed over 5 cm of every
# landmark coordinate and 1 degree of each noise sigma (docs/differentiable.md), with its standard error
value5, grads5 = delvjax.homing_loss_grad("env1", "delv", smoothing_cm=5.0, smoothing_deg=1.0, **kw)
g, se = grads5["landmarks"][0], grads5["standard_error"]["landmarks"][0]
print(
    f"landmark 0 at 5 cm: d loss / d(x, y) = ({g[0] * 100:+.4f} +- {se[0] * 100:.4f}, {g[1] * 100:+.4f} +- {se[1] * 100:.4f}) per m"
)
