#!/usr/bin/env python3
# Per scene of a merged collection (scripts/research/merge_scenes.sh), what
# a pairs file attempted: pairs within the scene, pairs from it to another
# scene, and the share of its labelled matchable pairs found (the labels'
# rule: overlap >= 0.25 and common-track ratio >= 0.15 where known).
#
#   scripts/research/collection_pairs_by_scene.py PAIRS LABELS [PAIRS2 ...]
#
# PAIRS as gcn_matcher or gcn_adaptive_simulator --GcnMatching.pairs_path
# write them ("<name1> <name2>" per line), names "<scene>__<image>"; with
# more than one pairs file, one column group per file.
import collections
import sys


def scene(name):
    return name.split("__", 1)[0]


def read_labels(path):
    images = collections.Counter()
    matchable = set()
    in_pairs = False
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith("image,"):
                images[scene(line[len("image,"):])] += 1
            elif line.startswith("name1,"):
                in_pairs = True
            elif in_pairs and line and not line.startswith("#"):
                a, b, overlap, ct = line.split(",")[:4]
                overlap, ct = float(overlap), float(ct)
                if (overlap >= 0 or ct >= 0) and \
                        (overlap < 0 or overlap >= 0.25) and \
                        (ct < 0 or ct >= 0.15):
                    matchable.add(tuple(sorted((a, b))))
    return images, matchable


def count(path, matchable):
    within, cross, found = (collections.Counter() for _ in range(3))
    num_pairs = 0
    with open(path) as f:
        for line in f:
            names = line.split()
            if len(names) != 2:
                continue
            num_pairs += 1
            a, b = names
            if scene(a) == scene(b):
                within[scene(a)] += 1
                found[scene(a)] += tuple(sorted((a, b))) in matchable
            else:
                cross[scene(a)] += 1
                cross[scene(b)] += 1
    return num_pairs, within, cross, found


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: collection_pairs_by_scene.py PAIRS LABELS [PAIRS2 ...]")
    images, matchable = read_labels(sys.argv[2])
    paths = [sys.argv[1]] + sys.argv[3:]
    runs = [count(p, matchable) for p in paths]
    total = collections.Counter(scene(a) for a, _ in matchable)
    print("| scene | images | matchable | " +
          " | ".join("within / cross / recall" for _ in paths) + " |")
    print("|---|---:|---:|" + "---|" * len(paths))
    for name in sorted(images):
        cells = [f"{w[name]} / {c[name]} / {f[name] / max(1, total[name]):.3f}"
                 for _, w, c, f in runs]
        print(f"| {name} | {images[name]} | {total[name]} | " +
              " | ".join(cells) + " |")
    for path, (num_pairs, _, cross, _) in zip(paths, runs):
        num_cross = sum(cross.values()) // 2
        print(f"{path}: {num_pairs} pairs, {num_cross} across scenes "
              f"({100 * num_cross / max(1, num_pairs):.2f} %)")


main()
