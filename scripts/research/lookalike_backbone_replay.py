#!/usr/bin/env python3
# Replays the look-alike filter's tree and loop test (lookalike_decision.cc)
# with other orderings of the backbone's edges, to compare them against the
# truth (docs/lookalike.md, "Tried and dropped"; it replays the loop test only,
# not the view-parallax test):
#
#   colmap gcn_pair_filter --database_path DB --dry_run 1 \
#       --PairFilter.pairs_csv_path PAIRS.csv
#   scripts/research/lookalike_backbone_replay.py DB GT_DIR LABELS.csv PAIRS.csv
#
# DB is the matched database (inliers and keypoints are read from it), GT_DIR
# a COLMAP text model of the true cameras, LABELS.csv gcn_benchmark's
# labels/labels.csv. Orderings: "cells" (covered grid cells), "distinctive"
# (the filter's: inliers in cells few of each image's pairs reach, < 10
# counted as 0, ties by cells), "inliers". Per ordering it prints the tree
# edges whose images' true relative rotation exceeds 90 degrees (on an
# object with one print front and back: look-alikes), and the rejected
# pairs by label (M matchable, w weak, W nothing shared).
import collections, csv, math, sqlite3, sys
import numpy as np

db_path, gt_dir, labels_path, csv_path = sys.argv[1:5]
con = sqlite3.connect(db_path)
names = dict(con.execute("select image_id, name from images"))
size = {c: (float(w), float(h)) for c, w, h in con.execute("select camera_id, width, height from cameras")}
camera_of = dict(con.execute("select image_id, camera_id from images"))
kp = {i: np.frombuffer(d, np.float32).reshape(r, c)[:, :2] if d else np.zeros((0, 2))
      for i, r, c, d in con.execute("select image_id, rows, cols, data from keypoints")}
P = 2147483647
pairs = {}
for pid, r, d, cfg in con.execute("select pair_id, rows, data, config from two_view_geometries"):
    if r >= 15 and cfg in (2, 3, 4, 5, 6, 8):
        pairs[(pid // P, pid % P)] = np.frombuffer(d, np.uint32).reshape(r, 2)
labels = {}
for f in csv.reader(open(labels_path)):
    if len(f) == 4 and f[0] != 'name1':
        ov, ct = float(f[2]), float(f[3])
        labels[(f[0], f[1])] = labels[(f[1], f[0])] = 'M' if (ov >= .25 or ct >= .15) else ('W' if ov <= 0 and ct <= 0 else 'w')

def qmat(w, x, y, z):
    q = np.array([w, x, y, z]) / np.linalg.norm([w, x, y, z]); w, x, y, z = q
    return np.array([[1-2*(y*y+z*z), 2*(x*y-z*w), 2*(x*z+y*w)], [2*(x*y+z*w), 1-2*(x*x+z*z), 2*(y*z-x*w)], [2*(x*z-y*w), 2*(y*z+x*w), 1-2*(x*x+y*y)]])
def angle(R): return math.degrees(math.acos(np.clip((np.trace(R) - 1) / 2, -1, 1)))
gt = {}
for line in open(gt_dir + '/images.txt'):
    f = line.split()
    if not line.startswith('#') and len(f) >= 10 and f[9].lower().endswith(('.jpg', '.png', '.jpeg')):
        gt[f[9]] = qmat(*map(float, f[1:5]))
def truth(a, b): return angle(gt[b] @ gt[a].T) if a in gt and b in gt else -1

G = 8
def cell_of(image, idx):
    w, h = size[camera_of[image]]; p = kp[image][idx]
    return np.clip((G * p[:, 0] / w).astype(int), 0, G - 1) + G * np.clip((G * p[:, 1] / h).astype(int), 0, G - 1)
reach = {i: np.zeros(G * G) for i in kp}
partners = collections.Counter()
for (a, b), inl in pairs.items():
    for image, col in ((a, 0), (b, 1)):
        reach[image] += np.bincount(cell_of(image, inl[:, col]), minlength=G * G) >= 3
        partners[image] += 1

id_of = {n: i for i, n in names.items()}
def rot(r, p):
    return None if r[p + 'w'] == '' else qmat(*(float(r[p + k]) for k in 'wxyz'))
edges = []
for r in csv.DictReader(open(csv_path)):
    a, b = id_of[r['name1']], id_of[r['name2']]
    inl = pairs[(a, b)] if (a, b) in pairs else pairs[(b, a)][:, ::-1]
    ca, cb = cell_of(a, inl[:, 0]), cell_of(b, inl[:, 1])
    rare = (reach[a][ca] <= max(1, math.floor(0.35 * partners[a]))) & (reach[b][cb] <= max(1, math.floor(0.35 * partners[b])))
    e = dict(n1=r['name1'], n2=r['name2'], a=a, b=b, n=int(r['num_inliers']), cells=int(r['covered_cells']),
             distinctive=int(rare.sum()) if rare.sum() >= 10 else 0)
    essential, hs = rot(r, 'e'), [rot(r, 'h1'), rot(r, 'h2')][:int(r['num_h'])]
    planar = r['config'] in ('4', '5', '6')
    if planar and len(hs) == 1:
        e['rot'], e['alt'] = hs[0], [essential] if essential is not None else []
    else:
        e['rot'] = essential if not planar else None
        e['alt'] = ([essential] if essential is not None and e['rot'] is None else []) + hs
    e['truth'], e['label'] = truth(e['n1'], e['n2']), labels.get((e['n1'], e['n2']), 'W')
    edges.append(e)

def replay(name, key, k=4, max_error=30, min_evidence=60):
    order = sorted(range(len(edges)), key=lambda i: key(edges[i]) + (-edges[i]['n'], i))
    taken, votes = collections.Counter(), collections.Counter()
    for i in order:
        for image in (edges[i]['a'], edges[i]['b']):
            if taken[image] < k: taken[image] += 1; votes[i] += 1
    parent = {}
    def find(x):
        while parent.get(x, x) != x: x = parent[x]
        return x
    tree = []
    for from_backbone in (True, False):
        for i in order:
            if (votes[i] == 2) != from_backbone or edges[i]['rot'] is None: continue
            x, y = find(edges[i]['a']), find(edges[i]['b'])
            if x != y: parent[x] = y; tree.append(i)
    adjacency = collections.defaultdict(list)
    for i in tree:
        e = edges[i]; adjacency[e['a']].append((e['b'], e['rot'])); adjacency[e['b']].append((e['a'], e['rot'].T))
    absolute, component = {}, {}
    for root in sorted(names):
        if root in absolute: continue
        absolute[root], component[root], queue = np.eye(3), root, [root]
        while queue:
            x = queue.pop(0)
            for y, R in adjacency[x]:
                if y not in absolute: absolute[y], component[y] = R @ absolute[x], root; queue.append(y)
    rejected = []
    for i, e in enumerate(edges):
        if i in tree or e['n'] < min_evidence or component.get(e['a']) != component.get(e['b']): continue
        candidates = ([e['rot']] if e['rot'] is not None else []) + [R for R in e['alt'] if R is not None]
        chained = absolute[e['b']] @ absolute[e['a']].T
        if candidates and min(angle(R.T @ chained) for R in candidates) > max_error: rejected.append(i)
    by_label = collections.Counter(edges[i]['label'] for i in rejected)
    print(f"{name:12s} tree edges over 90 deg: {sum(edges[i]['truth'] > 90 for i in tree):2d}  rejected {len(rejected):3d} "
          f"(matchable {by_label['M']}, weak {by_label['w']}, nothing shared {by_label['W']})")

replay('cells', lambda e: (-e['cells'],))
replay('distinctive', lambda e: (-e['distinctive'], -e['cells']))
replay('inliers', lambda e: ())
