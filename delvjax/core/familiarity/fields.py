"""Heading fields of a familiarity model (docs/familiarity.md §3.1): at every query point the agent
turns through the full circle (`n_turns` equal turns) from heading 0 and takes the most familiar view;
its world heading is compared with the route's direction at the nearest point of the route. Points
run `POINT_WIDTH` at a time (each renders a panorama, in a colour or a mesh world: `following.ViewSource`)."""

from __future__ import annotations

import equinox as eqx
import jax
import jax.numpy as jnp
from jax import Array
from jax.typing import ArrayLike

from ..batching import fixed_width_map
from ..geometry import TWO_PI, wrap
from .base import FamiliarityModel
from .following import MeshViews, WorldViews
from .ridf import rolled
from .route import Route, nearest_image, nearest_on_route

POINT_WIDTH = 8


class HeadingField(eqx.Module):
    """heading: (P,) rad, the most familiar world heading; value: (P,) its unfamiliarity; snapshot: (P,)
    the best-matching route image (-1: none kept); route_direction: (P,) rad at the nearest point of the
    route; distance: (P,) cm to the route; error_deg: (P,) |heading - route_direction|; curve: (P, R)
    the unfamiliarity of R equal turns counter-clockwise from the world heading curve_start (P,) rad
    (the RIDF)."""

    heading: Array
    value: Array
    snapshot: Array
    route_direction: Array
    distance: Array
    error_deg: Array
    curve: Array
    curve_start: Array


def full_turns(n_turns: int) -> Array:
    """(n_turns,) rad: 0, 2 pi / n, ... counter-clockwise."""
    return TWO_PI * jnp.arange(n_turns, dtype=jnp.float32) / n_turns


@eqx.filter_jit
def heading_field(
    model: FamiliarityModel, source: WorldViews | MeshViews, route: Route, points: ArrayLike, n_turns: int = 90
) -> HeadingField:
    """The `HeadingField` at every point (P, 2), views from `source` (module docstring)."""
    turns = full_turns(n_turns)

    def one(p: ArrayLike):
        choice = model.choose(source(p, jnp.float32(0.0), turns), turns)
        dist, _, along, _ = nearest_on_route(route, p)
        heading = wrap(choice.turn)
        error = jnp.abs(jnp.degrees(wrap(heading - along)))
        return heading, choice.value, choice.snapshot, along, dist, error, choice.curve, jnp.float32(0.0)

    out = fixed_width_map(one, (jnp.asarray(points, jnp.float32),), width=POINT_WIDTH)
    return HeadingField(*out)


@eqx.filter_jit
def stored_view_field(
    model: FamiliarityModel, views: ArrayLike, headings: ArrayLike, positions: ArrayLike, route: Route
) -> HeadingField:
    """The `HeadingField` of stored views (N, H, W) (an image database's) whose column 0 looked along
    `headings` (N,) at `positions` (N, 2): the RIDF over every whole-column roll; the reference is the
    column-0 heading of the nearest route image (as stored: no convention assumed about where a camera
    faced)."""
    views = jnp.asarray(views, jnp.float32)
    w = views.shape[-1]
    shifts = jnp.arange(w)
    turns = -TWO_PI * shifts.astype(jnp.float32) / w  # a right roll turns a ccw panorama clockwise

    def one(args):
        view, h, p = args
        choice = model.choose(rolled(view, shifts), turns)
        dist, _, _, _ = nearest_on_route(route, p)
        reference = route.headings[nearest_image(route, p)]
        heading = wrap(h + choice.turn)
        error = jnp.abs(jnp.degrees(wrap(heading - reference)))
        ccw = choice.curve[jnp.mod(-shifts, w)]  # entry k: a turn of +2 pi k / W
        return heading, choice.value, choice.snapshot, reference, dist, error, ccw, h

    args = (views, jnp.asarray(headings, jnp.float32), jnp.asarray(positions, jnp.float32))
    return HeadingField(*jax.lax.map(one, args))
