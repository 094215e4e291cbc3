"""The hybrid of landmark and image homing that thesis §6.3.3 leaves as future work ("combining two
methods in a complementary manner"; docs/model.md §4.8): DELV where its arrangement matching
converges, an image method (MinWarping by default) where it does not.

DELV's answer is taken where it is valid, it sees as many landmarks as the home record holds
(occlusion or a merged blob changes the count, and the cyclic pairing then pairs wrong landmarks,
§3.2.4), and the root mean square of its matching residuals, sqrt(var / n) with var the minimised
sum of Eq 3.5, is at most `rms_max` cm. Elsewhere the image method's answer is taken; where
that is invalid too, DELV's (valid or not). Both are computed at every point (under `vmap` a branch
would compute both anyway).
"""

from __future__ import annotations

import jax.numpy as jnp
from jax import Array

from ..sensing import UnitMove
from ..settings import setting
from ..types import Real
from .base import HomingMethod
from .delv import DELV
from .minwarping import MinWarping


class Hybrid(HomingMethod):
    """DELV where it converges, else `image` (docs/model.md §4.8).

    landmarks: the DELV module (its settings and heading source); image: the method used where
    DELV does not converge; rms_max: the largest RMS matching residual (cm) that counts as converged.
    """

    landmarks: DELV = DELV()
    image: HomingMethod = MinWarping()
    rms_max: Real = setting(
        25.0,
        check="positive",
        unit="cm",
        formerly="hybrid_rms_max",
        help="DELV's largest RMS residual (Eq 3.5) taken as converged",
    )

    def landmark_answer(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array, Array]:
        """(DELV's angle, its validity, whether its matching converged: valid, as many blobs as the
        home record, RMS residual of Eq 3.5 at most `rms_max`)."""
        a_delv, v_delv, fit = self.landmarks.fit(home, view)
        # var is a difference of sums: rounding can leave it a hair below 0 where the fit is exact
        rms = jnp.sqrt(jnp.maximum(fit["var"], 0.0) / jnp.maximum(fit["n"], 1))
        return a_delv, v_delv, v_delv & (fit["n_home"] == fit["n_current"]) & (rms <= self.rms_max)

    def choice(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array, Array]:
        """(angle, valid, whether DELV's answer was taken)."""
        a_delv, v_delv, converged = self.landmark_answer(home, view)
        a_img, v_img = self.image(home, view)
        return combine(a_delv, v_delv, converged, a_img, v_img)

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        angle, valid, _ = self.choice(home, view)
        return angle, valid

    def reads_start_view(self) -> bool:
        return True

    def reads_image(self) -> bool | Array:
        return self.image.reads_image()

    def reads_gray(self, channel: str) -> bool | Array:
        return self.landmarks.reads_gray(channel) or self.image.reads_gray(channel)

    def reads_panorama(self) -> bool:
        return self.image.reads_panorama()

    def check_input(self, n_pix: int) -> None:
        self.image.check_input(n_pix)

    def parts(self) -> dict[str, HomingMethod]:
        return {"landmarks": self.landmarks, "image": self.image}


def combine(a_delv, v_delv, converged, a_img, v_img) -> tuple:
    """The hybrid's (answer, valid, DELV taken) from its parts' answers, elementwise: DELV's where it
    converged or the image method's is invalid, else the image method's. `answer` may be any per-point
    quantity of the two (an angle, a world direction, an error)."""
    use_delv = converged | ~v_img
    return jnp.where(use_delv, a_delv, a_img), jnp.where(use_delv, v_delv, v_img), use_delv


class HybridGate(HomingMethod):
    """DELV's answer where the hybrid takes it because DELV converged, invalid elsewhere
    (docs/model.md §4.8). With the image method's own map, `combine` gives the hybrid's map without
    searching the image method's hypotheses a second time (the `hybrid` study)."""

    hybrid: Hybrid = Hybrid()

    def __call__(self, home: UnitMove, view: UnitMove) -> tuple[Array, Array]:
        a_delv, _, converged = self.hybrid.landmark_answer(home, view)
        return a_delv, converged

    def reads_start_view(self) -> bool:
        return True

    def parts(self) -> dict[str, HomingMethod]:
        return {"hybrid": self.hybrid}
