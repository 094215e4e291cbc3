"""Shared hypothesis settings and strategies of the property tests."""

from __future__ import annotations

import math

from hypothesis import HealthCheck
from hypothesis import strategies as st

FAST = dict(deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])
# values of every wrong kind: non-finite, huge, strings, None, booleans, empty containers
JUNK = st.one_of(
    st.sampled_from([math.nan, math.inf, -math.inf, 10**400, "1", None, True, [], {}]),
    st.text(max_size=3),
    st.lists(st.integers(), max_size=2),
)
