"""Route following by familiarity, as Ardin et al. (2016) run it (docs/familiarity.md §3.2): at every
step the agent scans +-`scan_deg` about its heading in `scan_step_deg` steps, turns to the most
familiar view (the model's `choose`), adds N(0, heading_noise) and moves `step` cm. Leaving the route
by more than `off_route` cm, entering an obstacle or leaving the arena is an error: the agent is put
back on the nearest point of the route, facing along it. A trial succeeds within `goal_radius` of
the route's last image, else times out after `max_steps`. The heading is column 0's; the agent moves
`camera_offset` to the right of it (0 for rendered routes; a database's camera may look elsewhere). A windowed perfect memory searches the
route images about its last best match (`perfect_memory.window`). Move t of trial i draws from
fold_in(fold_in(key, i), t): the same numbers however the trials are chunked."""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array

from ..batching import fixed_width_map
from ..geometry import TWO_PI, unit, wrap
from ..images.rollouts import Field, status
from ..images.world import World
from ..mesh.mesh import Mesh
from ..rollouts.rules import RUNNING, SUCCESS, TIMEOUT
from .base import FamiliarityModel
from .mesh_views import MeshCamera, mesh_views_at
from .perfect_memory import PerfectMemory, window
from .ridf import rolled
from .route import Route, nearest_on_route
from .views import ViewCamera, views_at

TRIAL_WIDTH = 8  # trials per vectorised step: each renders a panorama a move (or reads a stored view)


class Following(eqx.Module):
    """The rules of a route-following trial (module docstring); lengths in cm, angles in deg."""

    step: Array | float = 4.0
    off_route: Array | float = 20.0
    goal_radius: Array | float = 20.0
    heading_noise_deg: Array | float = 0.0
    camera_offset: Array | float = 0.0  # rad: where column 0 looks, left of the direction of travel
    scan_deg: float = eqx.field(static=True, default=60.0)
    scan_step_deg: float = eqx.field(static=True, default=2.0)
    max_steps: int = eqx.field(static=True, default=400)

    def turns(self) -> Array:
        """(R,) the scanned turns, rad, from -scan_deg to +scan_deg."""
        n = int(round(2 * self.scan_deg / self.scan_step_deg)) + 1
        return jnp.radians(jnp.linspace(-self.scan_deg, self.scan_deg, n, dtype=jnp.float32))


class Trials(eqx.Module):
    """outcome: (T,) SUCCESS or TIMEOUT; steps: (T,) moves made; errors: (T,) returns to the route;
    path: (T, max_steps + 1, 2) cm (the last position repeated after the trial ends); value: (T,
    max_steps) the chosen view's unfamiliarity at every move (NaN after the end)."""

    outcome: Array
    steps: Array
    errors: Array
    path: Array
    value: Array


class Surroundings(eqx.Module):
    """arena (4,) [xmin, ymin, xmax, ymax]; cylinders (C, 3) [x, y, r]; boxes (K, 4): what ends a move
    (a radius -1 or an empty box never does)."""

    arena: Array
    cylinders: Array
    boxes: Array

    def field(self, route: Route) -> Field:
        """The obstacle and goal test of a trial (`core/images/rollouts.py` `status`); the goal is the route's end."""
        n = route.positions.shape[0]
        return Field(route.positions, jnp.zeros(n), jnp.ones(n, bool), route.positions[-1], self.arena,
                     self.cylinders, self.boxes)  # fmt: skip


class WorldViews(eqx.Module):
    """Views rendered in a colour world at any pose (`views.views_at`)."""

    world: World
    camera: ViewCamera

    def __call__(self, x: Array, heading: Array, turns: Array) -> Array:
        return views_at(self.world, self.camera, x, heading, turns)

    def surroundings(self) -> Surroundings:
        c, b = self.world.cylinders, self.world.boxes
        return Surroundings(
            arena=self.world.arena,
            cylinders=jnp.where(c[:, 3:4] > 0, c[:, :3], jnp.array([0.0, 0.0, -1.0])),  # padding never hits
            boxes=jnp.where(b[:, 4:5] > 0, b[:, :4], jnp.array([0.0, 0.0, -1.0, -1.0])),
        )


class MeshViews(eqx.Module):
    """Views rendered in a triangle-mesh world at any pose (`mesh_views.mesh_views_at`); arena (4,) [xmin, ymin,
    xmax, ymax]: leaving it ends a move (an agent walks through the grass, as in Ardin et al. 2016)."""

    mesh: Mesh
    camera: MeshCamera
    arena: Array

    def __call__(self, x: Array, heading: Array, turns: Array) -> Array:
        return mesh_views_at(self.mesh, self.camera, x, heading, turns)

    def surroundings(self) -> Surroundings:
        none = jnp.array([[0.0, 0.0, -1.0, -1.0]])  # a radius -1, an empty box: never hit
        return Surroundings(jnp.asarray(self.arena, jnp.float32), none[:, :3], none)


class StoredViews(eqx.Module):
    """The views of an image database (navipy's and BoB's nearest-snapshot rule): at x the stored view
    nearest to x, rolled by whole columns so that column 0 looks along each turned heading (a turn is
    rounded to the view's column width). views: (N, H, W); positions: (N, 2) cm; headings: (N,) rad
    (column 0's)."""

    views: Array
    positions: Array
    headings: Array
    area: Surroundings

    def __call__(self, x: Array, heading: Array, turns: Array) -> Array:
        i = jnp.argmin(jnp.sum((self.positions - x) ** 2, -1))
        w = self.views.shape[-1]
        k = jnp.round(wrap(heading + turns - self.headings[i]) / (TWO_PI / w)).astype(jnp.int32)
        return rolled(self.views[i], -k)  # column j of the result: column j + k of the stored view

    def surroundings(self) -> Surroundings:
        return self.area


ViewSource = WorldViews | MeshViews | StoredViews  # (x, heading, turns) -> (R, H, W) views; surroundings()


def one_trial(model: FamiliarityModel, source, route: Route, rules: Following, start, heading0, key):
    """One trial from `start` (2,) facing `heading0` rad, views from `source` (a `ViewSource`; module docstring)."""
    field = source.surroundings().field(route)
    turns = rules.turns()
    n_img = model.n_images()
    windowed = isinstance(model, PerfectMemory) and model.window_ahead > 0

    def move(x, heading, pointer, t):
        """(position, heading, error, best image, unfamiliarity) after move t."""
        active = window(n_img, pointer, model.window_ahead, model.window_behind) if windowed else None
        choice = model.choose(source(x, heading, turns), turns, None, active)
        z = jax.random.normal(jax.random.fold_in(key, t), (), dtype=jnp.float32)
        h = wrap(heading + choice.turn + jnp.radians(rules.heading_noise_deg) * z)
        moved = x + rules.step * unit(h - rules.camera_offset)
        dist, back, along, _ = nearest_on_route(route, moved)
        hit = status(field, moved, jnp.float32(-1.0))  # LANDMARK / ARENA / RUNNING (no goal test here)
        error = (dist > rules.off_route) | (hit != RUNNING)
        moved = jnp.where(error, back, moved)
        h = jnp.where(error, along + rules.camera_offset, h)
        return moved, h, error, choice.snapshot, choice.value

    def running(carry):
        return (carry[4] == RUNNING) & (carry[5] < rules.max_steps)

    def body(carry):  # one move of a running trial; a lane group stops when all of its trials have ended
        x, heading, pointer, errors, code, t, path, value = carry
        x, heading, error, best, v = move(x, heading, pointer, t)
        done = jnp.sqrt(jnp.sum((x - field.home) ** 2)) <= rules.goal_radius
        pointer = jnp.where(best >= 0, best, pointer)
        path = jax.lax.dynamic_update_index_in_dim(path, x, t, 0)
        value = jax.lax.dynamic_update_index_in_dim(value, v, t, 0)
        return x, heading, pointer, errors + error, jnp.where(done, SUCCESS, code), t + 1, path, value

    start = jnp.asarray(start, jnp.float32)
    at_goal = jnp.sqrt(jnp.sum((start - field.home) ** 2)) <= rules.goal_radius
    n = rules.max_steps
    carry = (start, jnp.asarray(heading0, jnp.float32), jnp.int32(-1), jnp.int32(0),
             jnp.where(at_goal, SUCCESS, RUNNING), jnp.int32(0), jnp.zeros((n, 2), jnp.float32), jnp.full(n, jnp.nan, jnp.float32))  # fmt: skip
    x, _, _, errors, code, steps, path, value = jax.lax.while_loop(running, body, carry)
    path = jnp.where((jnp.arange(n) < steps)[:, None], path, x)  # the last position repeated after the end
    return jnp.where(code == RUNNING, TIMEOUT, code), steps, errors, jnp.concatenate([start[None], path]), value


@eqx.filter_jit
def follow_route(
    model: FamiliarityModel, source: ViewSource, route: Route, rules: Following, starts, headings, key
) -> Trials:
    """Route-following trials from every start (T, 2) facing headings (T,) rad; trial i draws from
    fold_in(key, i)."""
    keys = jax.vmap(lambda i: jax.random.fold_in(key, i))(jnp.arange(starts.shape[0]))
    run = lambda s, h, k: one_trial(model, source, route, rules, s, h, k)  # noqa: E731
    outcome, steps, errors, path, value = fixed_width_map(run, (starts, headings, keys), width=TRIAL_WIDTH)
    return Trials(outcome=outcome, steps=steps, errors=errors, path=path, value=value)
