#!/usr/bin/python3
"""Mutation fuzzer of talus scene input: the shipped scenes, damaged.

Each mutant (a scene with keys deleted, duplicated, renamed or retyped,
extreme numbers, odd strings, huge arrays, deep nesting, swapped values,
probes and meshes that do not fit, a damaged DEM, a truncated or corrupted
file) goes through `talus validate`, `talus plan` and, for scenes cheap to
set up, a `talus run` capped at a few steps, each in its own temporary folder
with a time limit. Every invocation must pass the gate (tools/fuzz/gate.py):
no signal, exit code in {0, 1, 2, 130, 143}, exit-2 messages naming the file
and a JSON pointer (or line:column), nothing written on exit 2, and validate,
plan and run agreeing. Failing inputs are kept, one folder each, with a
README of the commands and what they printed; --replay runs them again.

  /usr/bin/python3 tools/fuzz_scenes.py --count 20000              # long form
  /usr/bin/python3 tools/fuzz_scenes.py --short                    # what ctest runs
  /usr/bin/python3 tools/fuzz_scenes.py --replay fuzz-failures     # saved inputs again

Exit status: 0 when every input passed the gate, 1 otherwise. Timeouts and
validate/plan running out of memory (std::bad_alloc under --memory-mib) are
counted and their inputs kept (under timeouts/, memory/), but do not fail the
gate.
Debian's python3, standard library only.
"""
import argparse
import collections
import concurrent.futures
import hashlib
import os
import random
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "fuzz"))
import gate  # noqa: E402
import mutate  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUN_STEPS = 3  # `talus run` mutants stop after this many steps


def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--talus", default=os.path.join(ROOT, "build", "bin", "talus"), help="the talus executable")
    p.add_argument("--scenes", default=os.path.join(ROOT, "share", "scenes"), help="folder of seed scenes")
    p.add_argument("--count", type=int, default=2000, help="number of mutants (default 2000, the short form)")
    p.add_argument("--seed", type=int, default=1, help="random seed; a seed and count give the same mutants")
    p.add_argument("--jobs", type=int, default=1, help="mutants checked in parallel")
    p.add_argument("--timeout", type=float, default=20.0, help="seconds per invocation before it is killed")
    p.add_argument("--run", choices=["none", "cheap"], default="cheap",
                   help="also `talus run` (capped at %d steps) the mutants of scenes that set up quickly" % RUN_STEPS)
    p.add_argument("--run-every", type=int, default=4, help="run one mutant in N of a cheap scene (default 4)")
    p.add_argument("--recheck-every", type=int, default=8,
                   help="plan (and run) also one refused mutant in N, expecting validate's words (default 8)")
    p.add_argument("--cheap-seconds", type=float, default=1.0,
                   help="a seed scene whose validate takes longer is not run (and, with --short, not fuzzed)")
    p.add_argument("--memory-mib", type=int, default=4096,
                   help="address-space limit of each talus process (0: none; sanitizer builds need none)")
    p.add_argument("--failures", default="fuzz-failures", help="folder for failing inputs (default ./fuzz-failures)")
    p.add_argument("--short", action="store_true",
                   help="the ctest form: cheap scenes only, validate and plan, fixed seed")
    p.add_argument("--replay", metavar="PATH", help="check the inputs saved in PATH (a failures folder or one case)")
    p.add_argument("--max-seconds", type=float, default=0,
                   help="stop starting mutants after this long and summarise those done (0: no limit)")
    p.add_argument("--quiet", action="store_true", help="only the summary")
    return p.parse_args()


def limit_memory(mib):
    # Set here, inherited by every talus process: a mutant asking for the
    # moon gets bad_alloc instead of the machine's memory.
    if mib > 0:
        resource.setrlimit(resource.RLIMIT_AS, (mib << 20, mib << 20))


def invoke(args, command, case_dir, scene_rel, extra=()):
    """Runs one talus command in case_dir; returns (code or 'timeout', stderr, seconds, new paths)."""
    before = set(os.listdir(case_dir))
    env = dict(os.environ, OMP_NUM_THREADS="1")
    env.pop("TALUS_PLUGIN_PATH", None)
    start = time.monotonic()
    try:
        p = subprocess.run([args.talus, command, scene_rel, *extra], cwd=case_dir, env=env, stdin=subprocess.DEVNULL,
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=args.timeout)
        code, err = p.returncode, p.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired as e:
        code, err = "timeout", (e.stderr or b"").decode("utf-8", "replace")
    seconds = time.monotonic() - start
    new = set(os.listdir(case_dir)) - before
    return code, err, seconds, new


class Case:
    """One mutant laid out as the shipped scenes are: scenes/NAME.json beside dem/."""

    def __init__(self, root, name, data, aux, dem_bytes):
        self.dir = root
        os.makedirs(os.path.join(root, "scenes"))
        self.scene = os.path.join("scenes", name + ".json")
        with open(os.path.join(root, self.scene), "wb") as f:
            f.write(data)
        for a in aux:
            with open(os.path.join(root, "scenes", a.name), "wb") as f:
                f.write(a.data)
        # The other shipped scenes beside it: a scene may name one (a hand-off's run-out scene).
        taken = {name + ".json"} | {a.name for a in aux}
        shipped = os.path.join(ROOT, "share", "scenes")
        for entry in os.listdir(shipped):
            if entry.endswith(".json") and entry not in taken:
                os.symlink(os.path.join(shipped, entry), os.path.join(root, "scenes", entry))
        dem = os.path.join(root, "dem")
        if dem_bytes is not None:
            os.makedirs(dem)
            for entry in os.listdir(os.path.join(ROOT, "share", "dem")):
                shutil.copy(os.path.join(ROOT, "share", "dem", entry), dem)
            with open(os.path.join(dem, "runout_valley.asc"), "wb") as f:
                f.write(dem_bytes)
        else:
            os.symlink(os.path.join(ROOT, "share", "dem"), dem)


def check_case(args, case, commands, recheck=True):
    """Runs the commands on a case; returns (results {command: (code, stderr, s)}, violations).

    What validate refuses, plan and run refuse with the same words (they run
    the same checks first): they are run on it only when `recheck`."""
    results, problems = {}, []
    for command in commands:
        if command != "validate" and results.get("validate", (0,))[0] != 0 and not recheck:
            continue
        extra = ("--out", "out", "--quiet") if command == "run" else ()
        code, err, seconds, new = invoke(args, command, case.dir, case.scene, extra)
        results[command] = (code, err, seconds)
        if code == "timeout":
            continue
        written = new if code == 2 else set()
        problems += ["%s: %s" % (command, p) for p in gate.check(command, case.scene, code, err, written)]
        if command != "run" and new:
            problems.append("%s wrote %s (it runs nothing)" % (command, ", ".join(sorted(new))))

    codes = {c: r[0] for c, r in results.items() if r[0] != "timeout"}
    problems += gate.agree(codes)
    # An out-of-memory ending names the command that ran out; it is counted apart (gate.DEFERRED).
    # The memory a refusal reports as available changes from one command to the next.
    same = lambda c: re.sub(r"this machine has [\d.]+ \w+ available", "this machine has M available",
                            re.sub(r"^error: talus \w+: out of memory", "error: talus: out of memory", results[c][1]))
    for other in ("plan", "run"):
        if codes.get("validate") == 2 and codes.get(other) == 2 and same(other) != same("validate"):
            problems.append("%s refuses with other words than validate" % other)
    return results, problems


def save(args, case, results, problems, notes, label):
    """Keeps a failing or timed-out case: its files and a README of what happened."""
    digest = hashlib.sha1(open(os.path.join(case.dir, case.scene), "rb").read()).hexdigest()[:12]
    where = os.path.join(args.failures, *({"timeout": ["timeouts"], "memory": ["memory"]}.get(label, [])), digest)
    if os.path.exists(where):
        return where
    shutil.copytree(case.dir, where, symlinks=False, ignore=shutil.ignore_patterns("out"))
    with open(os.path.join(where, "README.txt"), "w") as f:
        f.write("fuzz case %s (%s)\nmutations: %s\n\n" % (digest, label, "; ".join(notes)))
        for p in problems:
            f.write("VIOLATION: %s\n" % p)
        for command, (code, err, seconds) in results.items():
            extra = " --out out --quiet" if command == "run" else ""
            f.write("\n$ cd %s && OMP_NUM_THREADS=1 %s %s %s%s\n-> %s (%.2f s)\n%s" % (
                where, args.talus, command, case.scene, extra, code, seconds, err[-4000:]))
    return where


def seed_scenes(args):
    """The seed scenes with their validate time; the cheap ones are run too."""
    names = sorted(f[:-5] for f in os.listdir(args.scenes) if f.endswith(".json"))
    seeds = []
    for name in names:
        text = open(os.path.join(args.scenes, name + ".json"), encoding="utf-8").read()
        with tempfile.TemporaryDirectory(prefix="talus-fuzz-") as tmp:
            case = Case(os.path.join(tmp, "c"), name, text.encode(), [], None)
            code, err, seconds, _ = invoke(args, "validate", case.dir, case.scene)
        if code != 0:
            sys.exit("fuzz: the seed scene %s does not validate (%s):\n%s" % (name, code, err))
        seeds.append((name, mutate.parse(text), seconds))
    return seeds


def cap_steps(doc):
    t = mutate.member(doc, "time")
    if isinstance(t, mutate.Obj):
        for entry in t:
            if entry[0] == "max_steps":
                if mutate.is_number(entry[1]) and entry[1] > RUN_STEPS:
                    entry[1] = RUN_STEPS
                return
        t.append(["max_steps", RUN_STEPS])


def make_mutant(args, seeds, corpus, dem, index):
    rng = random.Random("%d:%d" % (args.seed, index))
    name, doc, cost = seeds[rng.randrange(len(seeds))]
    runs = args.run == "cheap" and cost <= args.cheap_seconds and index % args.run_every == 0
    ctx = {"corpus": corpus, "aux": [], "dem": dem if name == "runout_valley" else None,
           "prepare": cap_steps if runs else None}
    data, notes = mutate.mutate(rng, mutate.copy_of(doc), ctx)
    return name, data, ctx["aux"], ctx.get("dem_bytes"), notes, runs


def one(args, seeds, corpus, dem, index, tmp):
    if args.deadline and time.monotonic() > args.deadline:
        return None
    name, data, aux, dem_bytes, notes, runs = make_mutant(args, seeds, corpus, dem, index)
    case = Case(os.path.join(tmp, "m%d" % index), name, data, aux, dem_bytes)
    commands = ["validate", "plan"] + (["run"] if runs else [])
    results, problems = check_case(args, case, commands, recheck=index % args.recheck_every == 0)
    timed_out = any(r[0] == "timeout" for r in results.values())
    deferred = [p for p in problems if gate.DEFERRED in p]
    problems = [p for p in problems if gate.DEFERRED not in p]
    label = "violation" if problems else "memory" if deferred else "timeout" if timed_out else None
    kept = save(args, case, results, problems + deferred, ["seed " + name] + notes, label) if label else None
    shutil.rmtree(case.dir, ignore_errors=True)
    return index, name, results, problems, bool(deferred), kept


def replay(args):
    """Re-checks saved cases: every folder under PATH with a scenes/ folder."""
    cases = []
    for base, dirs, _ in os.walk(args.replay):
        if "scenes" in dirs:
            cases.append(base)
            dirs[:] = []
    failed = 0
    for where in sorted(cases):
        with tempfile.TemporaryDirectory(prefix="talus-fuzz-") as tmp:
            shutil.copytree(where, os.path.join(tmp, "c"))
            case = Case.__new__(Case)
            case.dir = os.path.join(tmp, "c")
            scenes = [f for f in os.listdir(os.path.join(case.dir, "scenes")) if f.endswith(".json")]
            case.scene = os.path.join("scenes", scenes[0])
            shutil.rmtree(os.path.join(case.dir, "out"), ignore_errors=True)
            _, problems = check_case(args, case, ["validate", "plan", "run"])
        failed += bool(problems)
        print("%s %s%s" % ("FAIL" if problems else "ok  ", where, "".join("\n     " + p for p in problems)))
    print("%d of %d saved cases still fail the gate" % (failed, len(cases)))
    return 1 if failed else 0


def main():
    args = arguments()
    if not os.access(args.talus, os.X_OK):
        sys.exit("fuzz: no talus executable at %s (build first, or give --talus)" % args.talus)
    args.failures = os.path.abspath(args.failures)
    limit_memory(args.memory_mib)
    if args.replay:
        return replay(args)
    seeds = seed_scenes(args)
    corpus = [doc for _, doc, _ in seeds]
    if args.short:
        seeds = [s for s in seeds if s[2] <= args.cheap_seconds]
        args.run = "none"
    dem_path = os.path.join(ROOT, "share", "dem", "runout_valley.asc")
    dem = open(dem_path, "rb").read() if os.path.exists(dem_path) else None
    tally = collections.Counter()
    failures, slowest = [], []
    start = time.monotonic()
    args.deadline = start + args.max_seconds if args.max_seconds > 0 else 0
    with tempfile.TemporaryDirectory(prefix="talus-fuzz-") as tmp, \
            concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        jobs = [pool.submit(one, args, seeds, corpus, dem, i, tmp) for i in range(args.count)]
        done = 0
        for job in concurrent.futures.as_completed(jobs):
            if job.result() is None:
                continue  # past --max-seconds
            done += 1
            index, name, results, problems, deferred, kept = job.result()
            tally["memory"] += deferred
            for command, (code, _, seconds) in results.items():
                tally[(command, code if code == "timeout" or code >= 0 else "signal")] += 1
                slowest.append((seconds, index, name, command))
            slowest = sorted(slowest, reverse=True)[:5]
            if problems:
                failures.append((index, name, problems, kept))
                if not args.quiet:
                    print("FAIL mutant %d of %s: %s\n     kept in %s" % (index, name, problems[0], kept), flush=True)
            if not args.quiet and done % 500 == 0:
                print("fuzz: %d of %d mutants, %d failing, %.0f s" % (done, args.count, len(failures),
                                                                     time.monotonic() - start), flush=True)
    print("fuzz: %d mutants of %d seed scenes, seed %d, %.0f s" % (done, len(seeds), args.seed,
                                                                  time.monotonic() - start))
    for command in ("validate", "plan", "run"):
        row = {k[1]: v for k, v in tally.items() if k[0] == command}
        if row:
            print("  %-8s %s" % (command, "  ".join("%s: %d" % (k, row[k]) for k in sorted(row, key=str))))
    print("  slowest: " + ", ".join("%s of mutant %d (%s) %.1f s" % (c, i, n, t) for t, i, n, c in slowest[:3]))
    print("  out of memory (validate/plan, left to the memory estimate): %d" % tally["memory"])
    print("  gate: %d mutants failed%s" % (len(failures), "; kept in " + args.failures if failures else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
