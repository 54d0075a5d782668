#!/usr/bin/env python3
"""Confusion matrix of the contrast diagnosis on foreign truth, over draws.

    foreign_confusion.py [--model NAME] DRAW_FOLDER...
      each DRAW_FOLDER holds sets/ (make_foreign_lab_sets.sh: every set's metadata.toml carries
      [test] notes = "truth: ...") and diag/diagnose.json (`shard diagnose` of those sets); the
      two-rate sets' own diagnosis (rates_null and rates against the reference) in
      diag_rates/diagnose.json is read too when the folder has it. With --model NAME other than
      random (study_foreign_lab.sh's STUDY_MODEL), diag_NAME and diag_rates_NAME are read instead.

Prints one row per set: its truth and how often each verdict came over the draws, then the wrong
names: a named effect that is not in the set's truth ("no difference" and "unexplained
difference" name nothing, so they are never wrong; every name given to a set whose truth is none
or outside the library is wrong), then each set against its target: a library effect whose
contrast is clear (p < 1e-3) named in at least 3 of 4 such draws, a set with nothing hidden "no
difference" in every draw, an effect outside the library never named, two effects at once both
named or unexplained. Exits 2 on a folder without its sets or its diagnosis.
"""
import collections
import json
import os
import re
import sys

UNNAMED = ("no difference", "unexplained difference")


def truth_of(set_folder):
    path = os.path.join(set_folder, "metadata.toml")
    try:
        with open(path) as f:
            match = re.search(r'^\s*notes\s*=\s*"truth: ([^"]*)"', f.read(), re.MULTILINE)
    except OSError:
        sys.exit(f"{path}: not found; make the sets with make_foreign_lab_sets.sh")
    if not match:
        sys.exit(f'{path}: no [test] notes = "truth: ..."; make the sets with make_foreign_lab_sets.sh')
    return match.group(1)


def named_effects(verdict):
    """The library names in a verdict: none, one, or a pair written 'A + B'."""
    return [] if verdict in UNNAMED else [v.strip() for v in verdict.split("+")]


def read_report(folder, diagnosis):
    path = os.path.join(folder, diagnosis, "diagnose.json")
    try:
        with open(path) as f:
            report = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"{path}: {e}; run study_foreign_lab.sh on this draw")
    return [(s["name"], truth_of(os.path.join(folder, "sets", s["name"])), s["verdict"], s["p_value"])
            for s in report["sets"]]


def read_draw(folder, suffix):
    rows = read_report(folder, "diag" + suffix)
    rates = "diag_rates" + suffix
    if os.path.exists(os.path.join(folder, rates, "diagnose.json")):
        seen = {name for name, *_ in rows}
        rows += [row for row in read_report(folder, rates) if row[0] not in seen]
    return rows


def target(truth, verdicts):
    """(what the set must show, met?) over its verdicts [(verdict, p), ...]."""
    effects = truth.split(",")
    if truth == "none":
        met = sum(v == "no difference" for v, _ in verdicts)
        return f"no difference in every draw: {met} of {len(verdicts)}", met == len(verdicts)
    if truth == "outside":
        met = sum(not named_effects(v) for v, _ in verdicts)
        return f"never named: {met} of {len(verdicts)}", met == len(verdicts)
    clear = [v for v, p in verdicts if p < 1e-3]
    if len(effects) > 1:
        met = sum(sorted(named_effects(v)) == sorted(effects) or v == "unexplained difference" for v, _ in verdicts)
        return f"both named or unexplained: {met} of {len(verdicts)}", met == len(verdicts)
    named = sum(named_effects(v) == effects for v in clear)
    need = -(-3 * len(clear) // 4)  # 3 of 4, rounded up
    return f"named in {named} of {len(clear)} draws with p < 1e-3", named >= need


def main():
    args = sys.argv[1:]
    suffix = ""
    if args[:1] == ["--model"]:
        if len(args) < 2:
            sys.exit("--model needs a name (random or flat_zones)\n" + __doc__)
        suffix = "" if args[1] == "random" else "_" + args[1]
        args = args[2:]
    if not args:
        sys.exit(__doc__)
    rows = collections.OrderedDict()
    per_set = collections.OrderedDict()
    wrong, verdicts = [], 0
    for folder in args:
        for name, truth, verdict, p in read_draw(folder, suffix):
            rows.setdefault((name, truth), collections.Counter())[verdict] += 1
            per_set.setdefault((name, truth), []).append((verdict, p))
            verdicts += 1
            allowed = set(truth.split(","))
            wrong += [(folder, name, effect) for effect in named_effects(verdict) if effect not in allowed]
    print(f"| set | truth | verdicts over {len(args)} draws |\n|---|---|---|")
    for (name, truth), counts in rows.items():
        cells = ", ".join(f"{v} {n}" for v, n in counts.most_common())
        print(f"| {name} | {truth} | {cells} |")
    right = sum(n for (name, truth), counts in rows.items() for v, n in counts.items()
                if named_effects(v) and all(e in truth.split(",") for e in named_effects(v)))
    print(f"\nverdicts: {verdicts}; naming only true effects: {right}; wrong names: {len(wrong)}")
    for folder, name, effect in wrong:
        print(f"  wrong: {folder}: set {name} named {effect}")
    print("\n| set | target | met |\n|---|---|---|")
    for (name, truth), vs in per_set.items():
        text, met = target(truth, vs)
        print(f"| {name} | {text} | {'yes' if met else 'no'} |")


if __name__ == "__main__":
    main()
