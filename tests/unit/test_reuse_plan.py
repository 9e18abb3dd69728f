"""A reused run must have been made with the plan the test makes now.

``RockTest.run(reuse=True)`` (and ``bonded-lattice validate --reuse``) returns the summary an
earlier run left in the folder.  Before, any summary was accepted, so a folder made with other
options (or under older defaults) silently carried its old loading or damping into new results:
the validation's 2D N = 4 held-end-layers run had been made at a quarter of the papers' damping
and was read back as if at the papers' damping.  Now the stored plan is compared with today's.
"""

from __future__ import annotations

import json
from dataclasses import asdict

from bonded_lattice.experiment import RockTest, plan_changes
from bonded_lattice.rocks import get_rock


def _stored_test(tmp_path, **options) -> tuple[RockTest, dict]:
    test = RockTest(get_rock("quartz"), 2, "compression", 4, tmp_path, np_=1, progress=False,
                    **options)
    test._plan()
    summary = {"plan": asdict(test.plan), "relative_error": {"Cu": -0.1}}
    (tmp_path / "summary.json").write_text(json.dumps(summary))
    return test, summary


def test_a_run_with_the_same_plan_is_reused(tmp_path):
    _, summary = _stored_test(tmp_path, crossings=100.0, damping=1.0)
    again = RockTest(get_rock("quartz"), 2, "compression", 4, tmp_path, np_=1, progress=False,
                     crossings=100.0, damping=1.0)
    assert again.stored() == summary


def test_a_run_with_another_damping_is_made_again(tmp_path):
    stored_test, _ = _stored_test(tmp_path, crossings=100.0, damping=0.25)
    again = RockTest(get_rock("quartz"), 2, "compression", 4, tmp_path, np_=1, progress=False,
                     crossings=100.0, damping=1.0)
    assert again.stored() is None
    # the papers' eta is proportional to the damping factor: 4x between the two plans
    again._plan()
    assert again.plan.eta == 4 * stored_test.plan.eta


def test_plan_changes_names_the_keys_that_differ():
    assert plan_changes({"eta": 1.0, "dt": 2.0}, {"eta": 1.0, "dt": 2.0}) == ""
    # a relative difference below 1e-9 is round-off of the same computation
    assert plan_changes({"eta": 1.0}, {"eta": 1.0 + 1e-12}) == ""
    assert plan_changes({"eta": 1.0, "schedule": "constant"},
                        {"eta": 4.0, "schedule": "stepwise"}) == \
        "eta 1.0 -> 4.0, schedule 'constant' -> 'stepwise'"
    # keys an older summary lacks are not compared
    assert plan_changes({}, {"elastic_load": "tension"}) == ""
