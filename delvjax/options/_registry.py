"""The names of the methods: CLI and API names -> method modules (the edge; docs/model.md §3-4).

Nothing under jit takes a name: the edge looks a name up here once and passes the module on.
A new method is one module file in `delvjax/core/methods/` and one line in REGISTRY (its import
beside the others); its class is then public (`delvjax.<Class>`, `public_classes`) and documented
(docs/api.md and docs/options.md are made from the registry when the site is built, docs/_ext/generated.py).
"""

from __future__ import annotations

import dataclasses

import jax

from ..core.errors import InputError, did_you_mean
from ..core.methods.acv import ACV
from ..core.methods.alv import ALV
from ..core.methods.base import HomingMethod
from ..core.methods.cartwright_collett import CartwrightCollett
from ..core.methods.delv import DELV
from ..core.methods.delv_gap import DELVGap
from ..core.methods.delv_refined import DELVRefined
from ..core.methods.heading import Compass, VisualCompass
from ..core.methods.hybrid import Hybrid
from ..core.methods.method_set import MethodSet
from ..core.methods.mfdid import MFDID
from ..core.methods.minwarping import MinWarping
from ..core.methods.warping import Warping
from ..core.methods.warping2d import Warping2D
from ..core.settings import declared

# name: (module instance, one-line description). A new method is one line here.
REGISTRY: dict[str, tuple[HomingMethod, str]] = {
    "delv": (DELV(), "DELV, no compass: all cyclic shifts x n_heading heading hypotheses (thesis ch. 3-4)"),
    "delv-compass": (DELV(heading=Compass()), "DELV with a compass: only the cyclic shift is searched (thesis ch. 5)"),
    "delv-visual": (DELV(heading=VisualCompass()), "DELV with the visual compass of docs/model.md §4.4 (thesis 5.3.2)"),
    "alv": (ALV(), "average landmark vector with a compass (Lambrinos 2000; thesis 3.3.2)"),
    "alv-visual": (ALV(heading=VisualCompass()), "ALV with the visual compass (thesis 5.3.2)"),
    "acv": (ACV(), "average correction vector with a compass (Hong 1992; thesis Eq 5.2)"),
    "acv-visual": (ACV(heading=VisualCompass()), "ACV with the visual compass (thesis 5.3.2)"),
    "warping": (Warping(), "predictive image matching over alpha x rho x psi, no compass (Franz 1998; thesis 4.2)"),
    "mfdid": (MFDID(), "matched-filter descent in image distances with a compass (Moller & Vardy 2006)"),
    "minwarping": (
        MinWarping(),
        "MinWarping on gray panoramas: alpha x psi, each column's best distance (Moller 2009)",
    ),
    "hybrid": (Hybrid(), "DELV where its matching converges, else MinWarping (thesis 6.3.3's future work)"),
    "warping2d": (Warping2D(), "2D-Warping on gray panoramas: alpha x psi x rho, one distance for all (Moller 2009)"),
    "cc": (CartwrightCollett(), "snapshot model of Cartwright & Collett 1983 (landmarks only) with a compass"),
    "delv-agent": (
        DELV(order="agent"),
        "DELV, no compass, the current list in the agent frame (the earlier order; docs/model.md §3.3)",
    ),
    "delv-compass-agent": (
        DELV(heading=Compass(), order="agent"),
        "DELV with a compass, the current list in the agent frame (the earlier order; docs/model.md §3.3)",
    ),
    "delv-gap": (DELVGap(), "DELV, no compass, gap-aware matching: pairings may skip landmarks (beyond the thesis)"),
    "delv-gap-compass": (DELVGap(heading=Compass()), "DELV with a compass and gap-aware matching (beyond the thesis)"),
    "delv-refined": (
        DELVRefined(),
        "DELV, no compass, heading and home vector refined by least squares after the 1 deg search (beyond the thesis)",
    ),
}
METHODS: dict[str, HomingMethod] = {name: module for name, (module, _) in REGISTRY.items()}
DESCRIPTIONS: dict[str, str] = {name: text for name, (_, text) in REGISTRY.items()}


def public_classes() -> dict[str, type[HomingMethod]]:
    """The classes of the registered methods by class name, in registry order (read now: a method
    registered later counts): what `delvjax` exports (`from delvjax import MinWarping`) and
    docs/api.md documents. The one list of public methods: nothing else names them."""
    return {type(m).__name__: type(m) for m in METHODS.values()}


def register(name: str, module: HomingMethod, description: str) -> None:
    """Add a method under `name` (a line of REGISTRY, made at run time: a method of your own). Its
    declared settings (`core/settings.py`) become CLI flags, API keywords and sweep axes, its class
    an attribute of `delvjax` (`public_classes`)."""
    if not isinstance(module, HomingMethod):
        raise InputError("method", module, "must be a HomingMethod module")
    REGISTRY[name] = (module, description)
    METHODS[name] = module
    DESCRIPTIONS[name] = description


def unregister(name: str) -> None:
    """Remove a method added by `register`."""
    for table in (REGISTRY, METHODS, DESCRIPTIONS):
        table.pop(name, None)


def get_method(name: str) -> HomingMethod:
    """The module registered under `name`; `InputError` naming the field otherwise."""
    if not isinstance(name, str) or name not in METHODS:
        raise InputError(
            "method", name, f"unknown method{did_you_mean(name, METHODS)} (choose from {', '.join(METHODS)})"
        )
    return METHODS[name]


def configure(method: HomingMethod, **settings) -> HomingMethod:
    """`method` with those of `settings` (public option names, validated field values) that are its
    own declared settings replaced (a `MethodSet`: each of its methods); settings a method does not
    have are left to the others (e.g. `levels` is DELV's)."""
    if isinstance(method, MethodSet):
        return dataclasses.replace(method, methods=tuple(configure(m, **settings) for m in method.methods))
    own = declared(type(method))
    changes = {own[k][0]: v for k, v in settings.items() if v is not None and k in own}
    for name, part in method.parts().items():  # a method made of methods (the hybrid): each its own
        new = configure(part, **settings)
        if new is not part:
            changes[name] = new
    return dataclasses.replace(method, **changes) if changes else method


def owns(method: HomingMethod, option: str) -> bool:
    """Whether `method` (or, for a `MethodSet`, one of its methods) declares the setting `option`."""
    return bool(declaring(method, option))


def reads_compass(method: HomingMethod) -> bool:
    """Whether `method` holds a `Compass` anywhere (its heading source, a part's, a `MethodSet`'s methods'):
    the only readers of the compass reading and so of its noise (docs/model.md §4.4)."""
    is_compass = lambda x: isinstance(x, Compass)  # noqa: E731
    return any(is_compass(x) for x in jax.tree.leaves(method, is_leaf=is_compass))


def declaring(method: HomingMethod, option: str) -> tuple[type, ...]:
    """The classes in `method` (itself, a `MethodSet`'s methods, a method's parts) that declare `option`."""
    if isinstance(method, MethodSet):
        return tuple(dict.fromkeys(t for m in method.methods for t in declaring(m, option)))
    mine = (type(method),) if option in declared(type(method)) else ()
    return tuple(dict.fromkeys((*mine, *(t for p in method.parts().values() for t in declaring(p, option)))))


def method_set(method: str, names) -> tuple[MethodSet, tuple[str, ...]]:
    """The `MethodSet` of the methods `names` (a list of registry names containing `method`) that runs
    `method`; validated: `InputError` naming "method_set"."""
    get_method(method)
    if names is None:
        names = (method,)
    if isinstance(names, (str, bytes)) or not hasattr(names, "__iter__"):
        raise InputError("method_set", names, "must be a list of method names")
    names = tuple(names)
    unknown = [m for m in names if m not in METHODS]
    if unknown:
        raise InputError(
            "method_set",
            list(names),
            f"unknown method {unknown[0]!r}{did_you_mean(unknown[0], METHODS)} (choose from {', '.join(METHODS)})",
        )
    if method not in names:
        raise InputError("method_set", list(names), f"must contain the method {method!r}")
    return MethodSet(methods=tuple(METHODS[m] for m in names), index=names.index(method)), names
