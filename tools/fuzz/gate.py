"""The gate every talus invocation on a mutant must pass (tools/fuzz_scenes.py).

- no signal, and an exit code in {0, 1, 2, 130, 143};
- no sanitizer report;
- a command that runs nothing (validate, plan) exits 0 or 2: 1 means an
  uncaught failure, not bad input;
- exit 1 or 2: every line of stderr is an "error: " line, an indented
  continuation (a hint) or the closing "N errors in FILE; nothing was run.";
- exit 2: every error line names the scene file and a JSON pointer
  ("error: FILE: /..."), or a line and column for a syntax error
  ("error: FILE:L:C: ..."), with one "error: " only;
- exit 2: nothing was written (no output folder, no new file beside the scene).
The consistency of validate, plan and run on one mutant is checked by
`agree`: what validate accepts, plan and run accept too.
"""
import re
import signal

ALLOWED_EXIT = {0, 1, 2, 130, 143}
SANITIZER = re.compile(r"(AddressSanitizer|UndefinedBehaviorSanitizer|LeakSanitizer|runtime error: )")
DEFERRED = "memory: "
# ASan reports a failed allocation itself instead of throwing std::bad_alloc.
ASAN_OUT_OF_MEMORY = re.compile(r"(allocation-size-too-big|out-of-memory|allocator is out of memory|"
                                r"exceeds maximum supported size)")
SUMMARY = re.compile(r"^\d+ errors? in .*; nothing was run\.$")
# `talus study`: each failing variant's errors under a header, and a closing count.
VARIANT_HEADER = re.compile(r"^variant \d+ \(.*\):$")
STUDY_SUMMARY = re.compile(r"^\d+ of \d+ variants of .* cannot run; nothing was run\.$")
# A variant's errors name the base scene and the variant; a base that is not JSON is named with line:column.
STUDY_NAMES = r"(.+ \[variant \d+: .*\]: /|[^ ]+:\d+:\d+: )"


def signal_name(code):
    try:
        return signal.Signals(-code).name
    except ValueError:
        return "signal %d" % -code


def check(command, scene, code, stderr, written):
    """Violations (short strings) of one invocation; [] when it passes.

    scene: the scene (or study) path as given on the command line; written:
    paths the invocation created that it must not have (for exit 2)."""
    study = command == "study"
    problems = []
    if code < 0:
        return ["killed by %s" % signal_name(code)]
    if SANITIZER.search(stderr) and ASAN_OUT_OF_MEMORY.search(stderr):
        return [DEFERRED + "%s ran out of memory under ASan" % command]
    if code not in ALLOWED_EXIT:
        problems.append("exit code %d" % code)
    if SANITIZER.search(stderr):
        problems.append("sanitizer report")
    if "out of memory (std::bad_alloc)" in stderr and code == 2:
        # An allocation the up-front estimate did not foresee (talus ends it
        # with exit 2 and a message, but no JSON path: nothing knows which key
        # asked for it). Counted apart (DEFERRED), kept, not failed; the
        # estimate should catch the scene before allocating.
        return [DEFERRED + "%s ran out of memory past the estimate" % command]
    if command in ("validate", "plan") and code == 1:
        if "bad_alloc" in stderr:
            # Out of memory for a scene far too large: the up-front memory
            # estimate is separate work; counted apart (DEFERRED), kept, not failed.
            problems.append(DEFERRED + "%s ran out of memory" % command)
        else:
            problems.append("exit 1 from %s (an uncaught failure, not an input error)" % command)
    if code in (1, 2):
        lines = [l for l in stderr.splitlines() if l.strip()]
        if not any(l.startswith("error: ") for l in lines):
            problems.append("no 'error: ' line on exit %d" % code)
        for l in lines:
            if l.startswith("error: ") or l[:1].isspace() or SUMMARY.match(l):
                continue
            if study and (VARIANT_HEADER.match(l) or STUDY_SUMMARY.match(l)):
                continue
            problems.append("line without 'error: ': %s" % l[:120])
            break
    if code == 2:
        # Whatever follows the file name: a pointer ("/" or "/a/0") or L:C.
        named = re.compile(r"^error: (" + re.escape(scene) + r"(: /|:\d+:\d+: )" + ("|" + STUDY_NAMES if study else "") +
                           ")")
        for l in stderr.splitlines():
            if l.startswith("error: ") and not named.match(l):
                problems.append("error without file and JSON pointer: %s" % l[:160])
                break
            if l.startswith("error: ") and ": error: " in l:
                problems.append("doubled 'error: ': %s" % l[:160])
                break
        if written:
            problems.append("exit 2 but wrote %s" % ", ".join(sorted(written))[:200])
    return problems


def agree(codes):
    """Violations of validate/plan/run disagreeing on one mutant; codes: {command: exit code}."""
    v = codes.get("validate")
    problems = []
    if v == 0:
        for other in ("plan", "run"):
            if codes.get(other) == 2:
                problems.append("%s refuses (exit 2) what validate accepts: a check that comes too late" % other)
    if v == 2:
        for other in ("plan", "run"):
            if other in codes and codes[other] not in (2, None):
                problems.append("%s exits %s where validate refuses" % (other, codes[other]))
    return problems
