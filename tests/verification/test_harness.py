#!/usr/bin/env python3
"""Tests of the verification harness itself (tools/verify.py): the case contract and registry, the wcsph stage's
running maximum of the density deviation as the harness reads it, a hard case that must be reported unstable when
its limit is exceeded, and the report's hard-case table and per-particle memory.

  python3 tests/verification/test_harness.py --talus build/bin/talus
"""
import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import types
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))

from verification import precision, registry, report, runner  # noqa: E402
from verification.cases import _util  # noqa: E402

TALUS = None
SCENE = os.path.join("tests", "verification", "water_drop_2d.json")
STATUS = re.compile(r"rho dev ([0-9.eE+-]+)% \(worst ([0-9.eE+-]+)% at t = ([0-9.eE+-]+) s\)")


def drop_case(limit):
    """A hard case made on the fly: the water drop, its worst density deviation limited to `limit`."""
    return types.SimpleNamespace(
        HARD_CASE=True, NAME="drop", TITLE="water drop", SCENE=SCENE, LADDER=[0.01], TOLERANCE={0.01: limit},
        STRESSES="impact on a floor", WORST_LABEL="max |rho/rho0 - 1| over the run",
        configure=lambda scene, dp, option: scene,
        worst=_util.worst_density_deviation,
        gates=lambda run: [("reached the end", run.summary["time"] >= 0.3 - 1e-9, f"t = {run.summary['time']:.3g} s")])


class Registry(unittest.TestCase):
    def test_every_hard_case_has_a_criterion_that_can_fail(self):
        cases = registry.load_cases()
        hard = [c for c in cases if registry.is_hard(c)]
        self.assertGreaterEqual(len(hard), 6)
        for c in hard:
            self.assertTrue(c.STRESSES and c.WORST_LABEL, c.NAME)
            for r in c.LADDER:
                self.assertTrue(math.isfinite(c.TOLERANCE[r]), f"{c.NAME} rung {r} has no finite limit")
            self.assertIn(getattr(c, "QUICK_INDEX", 0), range(len(c.LADDER)), c.NAME)

    def test_a_hard_case_without_a_limit_or_gates_is_refused(self):
        case = drop_case(0.05)
        registry.check_case(case, "drop")
        case.TOLERANCE = {}
        with self.assertRaisesRegex(SystemExit, "no TOLERANCE"):
            registry.check_case(case, "drop")
        del case.gates
        with self.assertRaisesRegex(SystemExit, "lacks gates"):
            registry.check_case(case, "drop")


class RunningMaximum(unittest.TestCase):
    """The drop's impact compresses the water by several per cent; it settles below 1 %: the summary must carry
    both the final value and the worst over the run, and a hard case must judge the worst."""

    @classmethod
    def setUpClass(cls):
        cls.out = tempfile.mkdtemp(prefix="talus-harness-")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.out)

    def run_drop(self, limit, sub):
        return runner.run_case(drop_case(limit), TALUS, ROOT, os.path.join(self.out, sub), threads=1)[0]

    def test_worst_is_the_running_maximum_not_the_final_value(self):
        result = self.run_drop(0.5, "a")
        self.assertTrue(result.hard)
        self.assertTrue(result.stable, result.failure)
        self.assertEqual(result.directory, os.path.join(self.out, "a", "runs", "drop", "variants", "001"))
        with open(os.path.join(result.directory, "summary.json")) as f:
            summary = json.load(f)
        m = STATUS.search(summary["stages"]["wcsph"])
        self.assertIsNotNone(m, summary["stages"]["wcsph"])
        final, worst, when = (float(g) for g in m.groups())
        self.assertGreater(worst, 2.0)  # per cent, at the impact
        self.assertLess(final, 1.0)
        self.assertGreater(worst, 2 * final)
        self.assertTrue(0.1 < when < 0.2, when)
        self.assertAlmostEqual(result.error, worst / 100, places=6)
        self.assertAlmostEqual(result.sim_time, 0.3, places=9)
        self.assertGreater(result.bytes_per_particle, 0)

    def test_a_run_above_its_limit_is_unstable(self):
        result = self.run_drop(0.01, "b")
        self.assertFalse(result.stable)
        self.assertFalse(result.passed)
        self.assertIn("above tolerance", result.failure)

    def test_reuse_judges_the_stored_run_again_without_running(self):
        first = self.run_drop(0.5, "d")
        self.assertEqual((first.commit, first.machine), (report.checkout_commit(), report.processor()))
        summary = os.path.join(first.directory, "summary.json")
        stamp = os.stat(summary).st_mtime_ns
        origin = os.path.join(self.out, "d", "runs", "drop", "origin.json")
        with open(origin, "w") as f:
            json.dump({"commit": "0ld0ld0", "machine": "Old CPU, 2 cores"}, f)  # as if the study ran elsewhere
        again = runner.run_case(drop_case(0.01), TALUS, ROOT, os.path.join(self.out, "d"), threads=1, reuse=True)[0]
        self.assertEqual(os.stat(summary).st_mtime_ns, stamp)  # talus did not run
        self.assertTrue(first.stable)
        self.assertFalse(again.stable)  # the stricter limit judged on the same run
        self.assertEqual(again.steps, first.steps)
        self.assertEqual((again.commit, again.machine), ("0ld0ld0", "Old CPU, 2 cores"))  # where the run was made
        # Without reuse the case starts afresh, from this checkout.
        fresh = runner.run_case(drop_case(0.5), TALUS, ROOT, os.path.join(self.out, "d"), threads=1)[0]
        self.assertNotEqual(os.stat(summary).st_mtime_ns, stamp)
        self.assertEqual(fresh.commit, report.checkout_commit())

    def test_restart_keeps_the_worst_value(self):
        folder = self.run_drop(0.5, "c").directory
        checkpoints = sorted(p for p in os.listdir(folder) if p.endswith(".checkpoint"))
        self.assertEqual(len(checkpoints), 2)
        restarted = os.path.join(self.out, "c-restart")
        shutil.copytree(folder, restarted)
        subprocess.run([TALUS, "run", os.path.join(folder, "base.json"), "--out", restarted, "--quiet", "--threads",
                        "1", "--restart", os.path.join(restarted, checkpoints[0]), "--summary",
                        os.path.join(restarted, "s.json")], check=True)
        with open(os.path.join(folder, "summary.json")) as f:
            first = STATUS.search(json.load(f)["stages"]["wcsph"]).group(2, 3)
        with open(os.path.join(restarted, "s.json")) as f:
            second = STATUS.search(json.load(f)["stages"]["wcsph"]).group(2, 3)
        self.assertEqual(first, second)  # the impact came before the checkpoint: only the checkpoint knows it


class Report(unittest.TestCase):
    def test_hard_case_table_and_memory_per_particle(self):
        out = tempfile.mkdtemp()
        try:
            case = drop_case(0.05)
            ok = runner.Result("drop", "default", 0.01, particles=1000, steps=10, wall=1.0, memory=20.0,
                               error=0.03, tolerance=0.05, passed=True, hard=True, stable=True, sim_time=0.3,
                               bytes_per_particle=20.0 * 1024 * 1024 / 1000, gates=[("reached the end", True, "t")])
            bad = runner.Result("drop", "default", 0.005, particles=4000, steps=10, wall=2.0, memory=40.0,
                                error=0.09, tolerance=0.05, failure="worst above", hard=True, sim_time=0.3,
                                gates=[("reached the end", False, "t = 0.1")])
            report.write([ok, bad], [case], out)
            text = open(os.path.join(out, "README.md")).read()
            self.assertIn("## Hard cases (stability)", text)
            self.assertIn("| drop | impact on a floor | 0.01 | 1000 | 10 | 0.3 |", text)
            self.assertIn("20.5 KiB", text)
            self.assertIn("**NO**: worst above", text)
            self.assertIn("reached the end: FAILED (t = 0.1)", text)
            rows = report.read_previous(out, exclude=set(), known={"drop"})
            self.assertEqual([r.stable for r in rows], [True, False])
            self.assertTrue(all(r.hard for r in rows))
            self.assertAlmostEqual(rows[0].sim_time, 0.3)
        finally:
            shutil.rmtree(out)


def water_case(name):
    return types.SimpleNamespace(NAME=name, TITLE=name, REFERENCE="r", ERROR_LABEL="e")


def water_result(case, option, resolution, error, passed=True, failure="", in_float="", commit=""):
    return runner.Result(case, option, resolution, particles=100, steps=10, wall=1.0, memory=20.0, error=error,
                         tolerance=0.1, passed=passed, failure=failure, in_float=in_float, commit=commit)


class PrecisionComparison(unittest.TestCase):
    """verify.py --compare-precision: rungs paired across the two reports, and the default decided from them."""

    def setUp(self):
        self.root = tempfile.mkdtemp()
        self.double, self.mixed = os.path.join(self.root, "double"), os.path.join(self.root, "mixed")
        os.makedirs(self.double)
        os.makedirs(self.mixed)
        self.cases = [water_case("still"), water_case("dry")]
        report.write([water_result("still", "walls=dbc", 0.02, 0.05, commit="aaa"),
                      water_result("still", "walls=dbc", 0.01, 0.02, commit="aaa"),
                      water_result("dry", "default", 1.0, 0.01, commit="aaa")], self.cases, self.double)

    def tearDown(self):
        shutil.rmtree(self.root)

    def compare(self, mixed_results):
        report.write(mixed_results, self.cases, self.mixed)
        page = os.path.join(self.double, "precision.md")
        allowed = precision.write(os.path.join(self.double, "results.csv"), os.path.join(self.mixed, "results.csv"), page)
        return allowed, open(page).read()

    def test_a_case_not_run_in_mixed_keeps_the_default_double(self):
        fields = "fluid: velocity, density; walls: density"
        allowed, text = self.compare([water_result("still", "precision=mixed, walls=dbc", 0.02, 0.055, in_float=fields, commit="bbb"),
                                      water_result("still", "precision=mixed, walls=dbc", 0.01, 0.02, in_float=fields, commit="bbb")])
        self.assertFalse(allowed)
        self.assertIn("not run in mixed precision: `dry`", text)
        self.assertIn("| walls=dbc | 0.02 | 0.05 | 0.055 | +10 % | +0.05 | 0.1 | pass | pass |", text)
        self.assertIn(f"| `still` | 2 | 2 | {fields} | 2 | 2 | +0.05 | bbb |", text)

    def test_a_rung_failing_only_in_mixed_is_named(self):
        allowed, text = self.compare([water_result("still", "precision=mixed, walls=dbc", 0.02, 0.05),
                                      water_result("still", "precision=mixed, walls=dbc", 0.01, 0.2, passed=False,
                                                   failure="error 0.2 above tolerance 0.1"),
                                      water_result("dry", "precision=mixed", 1.0, 0.01)])
        self.assertFalse(allowed)
        self.assertIn("fails in mixed precision only: `still` walls=dbc 0.01", text)
        self.assertIn("- mixed, walls=dbc 0.01: error 0.2 above tolerance 0.1", text)

    def test_a_deviation_only_mixed_has_blocks_the_default(self):
        deviation = water_result("still", "precision=mixed, walls=dbc", 0.01, 0.2, passed=False,
                                 failure="error 0.2 above tolerance 0.1")
        deviation.known = True
        allowed, text = self.compare([water_result("still", "precision=mixed, walls=dbc", 0.02, 0.05), deviation,
                                      water_result("dry", "precision=mixed", 1.0, 0.01)])
        self.assertFalse(allowed)
        self.assertIn("fails in mixed precision only: `still` walls=dbc 0.01", text)

    def test_every_rung_passing_in_mixed_allows_it_as_default(self):
        allowed, text = self.compare([water_result("still", "precision=mixed, walls=dbc", 0.02, 0.05),
                                      water_result("still", "precision=mixed, walls=dbc", 0.01, 0.02),
                                      water_result("dry", "precision=mixed", 1.0, 0.01)])
        self.assertTrue(allowed)
        self.assertIn("mixed precision may be the default", text)

    def test_rows_of_the_wrong_precision_are_refused(self):
        report.write([water_result("dry", "default", 1.0, 0.01)], self.cases, self.mixed)
        with self.assertRaisesRegex(SystemExit, "not run with --precision mixed"):
            precision.write(os.path.join(self.double, "results.csv"), os.path.join(self.mixed, "results.csv"),
                            os.path.join(self.double, "precision.md"))

    def test_the_report_links_the_comparison_and_a_rerun_case_says_where_it_ran(self):
        self.compare([water_result("dry", "precision=mixed", 1.0, 0.01)])
        rows = report.read_previous(self.double, exclude=set(), known={"still", "dry"})
        rows[-1].commit, rows[-1].machine = "ccc", "Some CPU, 2 cores"
        report.write(rows, self.cases, self.double, header="Other CPU, 4 cores, Linux, commit aaa")
        with open(os.path.join(self.double, "README.md")) as f:
            text = f.read()
        self.assertIn("[precision.md](precision.md)", text)
        self.assertEqual(report.stored_machine(self.double), "Other CPU, 4 cores, Linux, commit aaa")
        self.assertEqual(text.count("Run at commit"), 1)  # still's rows ran at the header's commit
        self.assertIn("Run at commit ccc on Some CPU, 2 cores (the rest of the report as named at the top).", text)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--talus", required=True)
    args, rest = parser.parse_known_args()
    TALUS = os.path.abspath(args.talus)
    unittest.main(argv=[sys.argv[0]] + rest)
