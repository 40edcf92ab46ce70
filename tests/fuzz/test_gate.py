"""The fuzz gate (tools/fuzz/gate.py) on made-up invocations: it passes what
the project promises and catches each kind of violation."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools", "fuzz"))
import gate  # noqa: E402
import mutate  # noqa: E402

SCENE = "scenes/a.json"


class Gate(unittest.TestCase):
    def test_passes_pointer_and_syntax_errors(self):
        err = ("error: scenes/a.json: /time/end: -1 is out of range; must be > 0\n"
               "       known: end\n"
               "error: scenes/a.json: /: expected an object\n"
               "2 errors in scenes/a.json; nothing was run.\n")
        self.assertEqual(gate.check("validate", SCENE, 2, err, set()), [])
        self.assertEqual(gate.check("plan", SCENE, 2, "error: scenes/a.json:3:7: JSON syntax error: x\n", set()), [])
        self.assertEqual(gate.check("run", SCENE, 1, "error: step 3 (t = 0.1 s): non-finite\n", set()), [])
        self.assertEqual(gate.check("validate", SCENE, 0, "", set()), [])

    def test_catches_each_violation(self):
        def one(command, code, err, written=()):
            problems = gate.check(command, SCENE, code, err, set(written))
            self.assertTrue(problems, (command, code, err))
            return problems[0]
        self.assertIn("SIGSEGV", one("validate", -11, ""))
        self.assertIn("exit code 134", one("run", 134, "error: x\n"))
        self.assertIn("without file and JSON pointer", one("validate", 2, "error: scenes/a.json: no kernel\n"))
        self.assertIn("without file and JSON pointer", one("validate", 2, "error: wcsph: no SPH kernel\n"))
        self.assertIn("no 'error: ' line", one("run", 2, "neighbour search: a periodic axis\n"))
        self.assertIn("line without 'error: '", one("run", 2, "error: scenes/a.json: /a: x\nstray line\n"))
        self.assertIn("exit 1 from validate", one("validate", 1, "error: KernelTable: bad h\n"))
        self.assertIn("doubled", one("validate", 2, "error: scenes/a.json: /plugins/0: error: plugin 'x'\n"))
        self.assertIn("wrote out", one("run", 2, "error: scenes/a.json: /x: bad\n", ["out"]))
        self.assertIn("sanitizer", one("validate", 0, "x.cpp:3:5: runtime error: signed integer overflow\n"))
        self.assertTrue(one("validate", 1, "error: std::bad_alloc\n").startswith(gate.DEFERRED))

    def test_validate_plan_and_run_agree(self):
        self.assertEqual(gate.agree({"validate": 0, "plan": 0, "run": 1}), [])
        self.assertEqual(gate.agree({"validate": 2, "plan": 2, "run": 2}), [])
        self.assertIn("too late", gate.agree({"validate": 0, "plan": 0, "run": 2})[0])
        self.assertTrue(gate.agree({"validate": 2, "plan": 0}))


class Mutants(unittest.TestCase):
    def test_round_trip_keeps_duplicates_and_raw_tokens(self):
        doc = mutate.parse('{"a": 1, "b": [1, 2]}')
        doc.append(["a", mutate.Raw("1e999")])
        self.assertEqual(mutate.dump(doc).replace("\n", "").replace(" ", ""), '{"a":1,"b":[1,2],"a":1e999}')

    def test_a_seed_gives_the_same_mutant(self):
        import random
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "share", "scenes",
                            "hydrostatic_2d.json")
        with open(path, encoding="utf-8") as f:
            text = f.read()
        ctx = lambda: {"corpus": [mutate.parse(text)], "aux": [], "dem": None, "prepare": None}
        a = [mutate.mutate(random.Random(k), mutate.parse(text), ctx())[0] for k in range(50)]
        b = [mutate.mutate(random.Random(k), mutate.parse(text), ctx())[0] for k in range(50)]
        self.assertEqual(a, b)
        self.assertGreater(len(set(a)), 40)


if __name__ == "__main__":
    unittest.main()
