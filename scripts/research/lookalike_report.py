#!/usr/bin/env python3
# The fold check's table (docs/lookalike.md) from the two runs of
# lookalike_benchmark.sh:
#
#   scripts/research/lookalike_report.py OUT/off.json OUT/on.json
#
# One Markdown row per scene and method, filter off → on: verified pairs,
# wrong verified pairs reaching the mapper, pairs the filter hid (wrong /
# matchable by the labels), registered images, accurate cameras with the
# median rotation error against the ground truth (a folded model is 90°+
# off), the fraction of the circle the registered cameras cover (RingCoverage
# in evaluation/alignment.h) against the ground truth's, and the filter's
# time against pairing + matching.
import json
import statistics
import sys


def runs(path):
    return {(s["name"], m["method"]): (s, m)
            for s in json.load(open(path))["scenes"] for m in s["methods"]}


def accurate(scene, method):
    sfm = method.get("sfm", {})
    errors = sfm.get("pose_errors", {})
    if "fraction_accurate" not in errors:
        return f'{sfm.get("num_registered", 0)}/{scene["num_images"]}, -'
    rotations = [i["rotation_error_deg"] for i in errors.get("images", [])
                 if i.get("rotation_error_deg", -1) >= 0]
    median = f"{statistics.median(rotations):.1f}°" if rotations else "-"
    return (f'{sfm["num_registered"]}/{scene["num_images"]}, '
            f'{round(100 * errors["fraction_accurate"])} % ({median})')


def ring(method):
    errors = method.get("sfm", {}).get("pose_errors", {})
    return errors.get("ring_coverage", -1), errors.get("gt_ring_coverage", -1)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: lookalike_report.py OFF.json ON.json")
    off, on = runs(sys.argv[1]), runs(sys.argv[2])
    print("| scene | method | verified | wrong verified reaching the mapper | "
          "hidden (wrong / matchable) | registered, accurate (median "
          "rotation error) | ring coverage (GT) | filter / pairing + matching |")
    print("|---|---|---:|---|---|---|---|---|")
    for key, (scene, m_off) in off.items():
        if key not in on:
            continue
        _, m_on = on[key]
        ring_off, ring_gt = ring(m_off)
        ring_on, _ = ring(m_on)
        print(f'| {scene["name"]} | {m_off["method"]} | {m_off["um"]} | '
              f'{m_off["num_verified_wrong"]} → {m_on["num_verified_wrong"]} | '
              f'{m_on.get("lookalike_removed", 0)} '
              f'({m_on.get("lookalike_removed_wrong", 0)} / '
              f'{m_on.get("lookalike_removed_matchable", 0)}) | '
              f'{accurate(scene, m_off)} → {accurate(scene, m_on)} | '
              f'{ring_off:.2f} → {ring_on:.2f} ({ring_gt:.2f}) | '
              f'{m_on.get("filter_seconds", 0):.2f} s / '
              f'{m_on["pairing_seconds"] + m_on["matching_seconds"]:.1f} s |')


if __name__ == "__main__":
    main()
