"""A simulation's events at the joints' position limits (issue 25: a joint reached its stop and
nothing said so; a start outside the limits was pushed inside silently)."""

import math

import numpy as np

import screwdyn


def test_the_ur5s_passive_run_lists_the_stop_it_reaches():
    ur5 = screwdyn.load("builtin:ur5")
    run = ur5.simulate(np.zeros(6), duration=1.0)
    assert len(run.events) == 1
    e = run.events[0]
    assert (e["kind"], e["joint"], e["side"]) == ("contact", "wrist_2_joint", "upper")
    assert e["bound"] == ur5.upper_limits[4] == 2 * math.pi
    # The contact time is where the recorded wrist_2 angle crosses 2π.
    k = int(np.argmax(run.q[:, 4] > e["bound"]))
    assert run.t[k - 1] <= e["t"] <= run.t[k]
    # Without the stops nothing is listed.
    assert ur5.simulate(np.zeros(6), duration=1.0, effects=False).events == []


def test_a_start_outside_the_limits_is_listed_and_not_moved():
    panda = screwdyn.load("builtin:panda")
    run = panda.simulate(np.zeros(7), duration=0.01)
    starts = [e for e in run.events if e["kind"] == "start_outside"]
    assert [(e["joint"], e["side"], e["t"], e["position"]) for e in starts] == [
        ("panda_joint4", "upper", 0.0, 0.0)
    ]
    assert starts[0]["bound"] == panda.upper_limits[3]
    assert run.q[0, 3] == 0.0
