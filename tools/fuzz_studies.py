#!/usr/bin/python3
"""Mutation fuzzer of talus study files: the shipped studies (share/studies),
damaged as tools/fuzz_scenes.py damages scenes (keys deleted, renamed and
retyped, extreme numbers, huge arrays, truncated files, ...), each through
`talus study --dry-run`, which checks the study and every variant and runs
nothing. Every invocation must pass the gate (tools/fuzz/gate.py): no signal,
exit 0 or 2, every error line naming the study file and a JSON pointer (or a
variant of the base scene), and nothing written at all. Failing inputs are
kept, one folder each, with a README of the command and what it printed.

  /usr/bin/python3 tools/fuzz_studies.py --count 5000     # long form
  /usr/bin/python3 tools/fuzz_studies.py --count 300      # what ctest runs

Exit status: 0 when every input passed the gate, 1 otherwise.
Debian's python3, standard library only.
"""
import argparse
import hashlib
import os
import random
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "fuzz"))
import fuzz_scenes  # noqa: E402
import gate  # noqa: E402
import mutate  # noqa: E402

ROOT = fuzz_scenes.ROOT


def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--talus", default=os.path.join(ROOT, "build", "bin", "talus"), help="the talus executable")
    p.add_argument("--studies", default=os.path.join(ROOT, "share", "studies"), help="folder of seed studies")
    p.add_argument("--count", type=int, default=300, help="number of mutants (default 300)")
    p.add_argument("--seed", type=int, default=1, help="random seed; a seed and count give the same mutants")
    p.add_argument("--timeout", type=float, default=20.0, help="seconds per invocation before it is killed")
    p.add_argument("--memory-mib", type=int, default=1024, help="address-space limit of each talus process")
    p.add_argument("--failures", default=os.path.join(ROOT, "fuzz-failures", "studies"),
                   help="folder for failing inputs")
    return p.parse_args()


def lay_out(root, name, data):
    """studies/NAME.json beside the shipped scenes, as share/ holds them."""
    os.makedirs(os.path.join(root, "studies"))
    os.symlink(os.path.join(ROOT, "share", "scenes"), os.path.join(root, "scenes"))
    study = os.path.join("studies", name + ".json")
    with open(os.path.join(root, study), "wb") as f:
        f.write(data)
    return study


def keep(args, root, study, code, err, notes, problems):
    digest = hashlib.sha1(open(os.path.join(root, study), "rb").read()).hexdigest()[:12]
    where = os.path.join(args.failures, digest)
    if not os.path.exists(where):
        shutil.copytree(root, where, symlinks=True)
        with open(os.path.join(where, "README.txt"), "w") as f:
            f.write("fuzz case %s\nmutations: %s\n\n" % (digest, "; ".join(notes)))
            for p in problems:
                f.write("VIOLATION: %s\n" % p)
            f.write("\n$ cd %s && %s study %s --dry-run --out out\n-> %s\n%s" % (where, args.talus, study, code,
                                                                                  err[-4000:]))
    return where


def main():
    args = arguments()
    if not os.access(args.talus, os.X_OK):
        sys.exit("fuzz: no talus executable at %s (build first, or give --talus)" % args.talus)
    args.failures = os.path.abspath(args.failures)
    fuzz_scenes.limit_memory(args.memory_mib)
    names = sorted(f[:-5] for f in os.listdir(args.studies) if f.endswith(".json"))
    seeds = [(n, mutate.parse(open(os.path.join(args.studies, n + ".json"), encoding="utf-8").read())) for n in names]
    corpus = [doc for _, doc in seeds]
    failed = timeouts = accepted = 0
    with tempfile.TemporaryDirectory(prefix="talus-fuzz-studies-") as tmp:
        for index in range(args.count):
            rng = random.Random("%d:%d" % (args.seed, index))
            name, doc = seeds[rng.randrange(len(seeds))]
            data, notes = mutate.mutate(rng, mutate.copy_of(doc), {"corpus": corpus, "aux": [], "dem": None})
            root = os.path.join(tmp, "m%d" % index)
            study = lay_out(root, name, data)
            code, err, _, new = fuzz_scenes.invoke(args, "study", root, study, ("--dry-run", "--out", "out"))
            accepted += code == 0
            if code == "timeout":
                timeouts += 1
                problems = ["timed out after %g s" % args.timeout]
            else:
                problems = gate.check("study", study, code, err, new if code == 2 else set())
                if code not in (0, 2):
                    problems.append("exit %s from a dry run (it runs nothing)" % code)
                if new:
                    problems.append("a dry run wrote %s" % ", ".join(sorted(new)))
            if problems:
                failed += 1
                where = keep(args, root, study, code, err, notes, problems)
                print("FAIL %d (%s): %s\n     kept in %s" % (index, name, "; ".join(problems), where))
            shutil.rmtree(root, ignore_errors=True)
    print("fuzz studies: %d mutants (%d accepted), %d failed the gate (%d timeouts)" % (args.count, accepted, failed,
                                                                                     timeouts))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
