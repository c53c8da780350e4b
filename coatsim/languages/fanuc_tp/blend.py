"""What a Fanuc controller does at the end of a motion, as the twin models it.

``FINE``: the robot stops at the point. ``CNT n`` (0 to 100) is not a distance: the robot keeps
n % of its speed through the point, rounding the corner as much as that takes, so the rounding
grows with the speed (CNT100 rounds as far as needed to keep full speed, CNT0 comes all the way
to the point like FINE; robot-forum.com thread 31486 "How does CNT exactly work?", the mh142
Fanuc wiki on motion instructions: "how much deceleration is ignored"). The twin's model: the
controller starts the next motion when the current one, braking at ``decel_mm_s2``, has slowed
to n % of its programmed speed v; the tool leaves the path that far from the point, the distance
the brake still had to run:

    accuracy_mm = (n / 100)² · v² / (2 · decel_mm_s2)

so CNT100 at 500 mm/s and 5 m/s² (the shipped cell's tool acceleration at ACC 100 %) rounds
25 mm from the corner, CNT20 1 mm. CNT0 is a stop. ``CR r`` (corner radius, an option of
newer controllers) rounds within r mm. The twin caps every rounding at half of each neighbouring
move, as for every language. The writer inverts the model to write the plan's accuracy.
"""

from __future__ import annotations

import math

#: The tool's braking deceleration the CNT model assumes (the shipped cell's ACC 100 %), mm/s².
DECEL_MM_S2 = 5000.0


def cnt_accuracy_mm(cnt: float, speed_mm_s: float, decel_mm_s2: float = DECEL_MM_S2) -> float:
    """The distance from the point where a ``CNT cnt`` motion at ``speed_mm_s`` leaves the path."""
    return (cnt / 100.0) ** 2 * speed_mm_s ** 2 / (2.0 * decel_mm_s2)


def cnt_for(accuracy_mm: float, speed_mm_s: float, decel_mm_s2: float = DECEL_MM_S2) -> int:
    """The CNT value (1 to 100) whose rounding is nearest ``accuracy_mm`` at ``speed_mm_s``
    (100 when even CNT100 rounds less)."""
    full = cnt_accuracy_mm(100.0, speed_mm_s, decel_mm_s2)
    return int(min(100, max(1, round(100.0 * math.sqrt(max(accuracy_mm, 0.0) / full)))))
