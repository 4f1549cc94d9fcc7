"""The liquid front's arrival at the section x = paper.SECTION_X and the rule of the flow turning
subcritical there, on the rows of a liquid time series (outputs.LIQUID_SERIES).

t0 = first time the front (front_bed_m) reaches the section; the flow "turns subcritical" at the
first time t > t0 from which Fr < 1 holds for at least HOLD_S seconds (or to the end of the run).
"""

import math

from .paper import SECTION_X

HOLD_S = 0.2


def first_time(rows, cond):
    for r in rows:
        if cond(r):
            return r["time_s"]
    return None


def subcritical_after_arrival(rows):
    t0 = first_time(rows, lambda r: r["front_bed_m"] >= SECTION_X)
    if t0 is None:
        return None, None
    return t0, subcritical_from(rows, t0)


def subcritical_from(rows, t0):
    """First time after t0 from which Fr < 1 holds for HOLD_S (or to the end), or None."""
    after = [r for r in rows if r["time_s"] >= t0 and not math.isnan(r["section_froude"])]
    i = 0
    while i < len(after):
        start = after[i]["time_s"]
        j = i  # the rows of the window [start, start + HOLD_S], while Fr < 1
        while j < len(after) and after[j]["time_s"] <= start + HOLD_S and \
                after[j]["section_froude"] < 1:
            j += 1
        if j == i:
            i += 1
        elif j < len(after) and after[j]["time_s"] <= start + HOLD_S:
            i = j + 1  # Fr >= 1 at j lies in the window of every start up to j
        elif after[j - 1]["time_s"] >= start + HOLD_S - 0.05 or j == len(after):
            return start
        else:
            i += 1
    return None
