#!/usr/bin/env python3
# How far each verified pair's relative translation direction lies from the
# truth, by label and COLMAP configuration (docs/lookalike.md, "Where it
# fails": translation-only look-alikes keep the true rotation, so only the
# direction can tell them):
#
#   scripts/research/translation_diagnose.py DB GT/images.txt LABELS.csv [PAIRS.csv]
#
# DB is a matched database (with the look-alike filter's hidden pairs
# restored: gcn_pair_filter --restore 1 on a copy), GT a COLMAP text model
# of the true cameras, LABELS.csv gcn_benchmark's labels/labels.csv
# (M: matchable, w: weak, x: sharing nothing). The direction comes from E
# (COLMAP's for calibrated pairs, K2^T F K1 otherwise), disambiguated by
# cheirality on 100 inliers. Prints, per label and configuration, the pairs,
# the median direction error and how many are more than 20 degrees off;
# PAIRS.csv, if given, gets one row per pair. Needs numpy.
import sqlite3, numpy as np, sys, csv, math
if len(sys.argv) not in (4, 5):
    sys.exit('usage: translation_diagnose.py DB GT/images.txt LABELS.csv [PAIRS.csv]')
db, gtp, labp = sys.argv[1:4]
con = sqlite3.connect(db)
cams = {r[0]: (r[1], np.frombuffer(r[4], np.float64)) for r in con.execute("select camera_id, model, width, height, params from cameras")}
imgs = {r[0]: (r[1], r[2]) for r in con.execute("select image_id, name, camera_id from images")}
kps = {}
for iid, rows, cols, data in con.execute("select image_id, rows, cols, data from keypoints"):
    kps[iid] = np.frombuffer(data, np.float32).reshape(rows, cols)[:, :2].astype(np.float64)
def K(cid):
    model, p = cams[cid]
    if model == 0: f, cx, cy = p[0], p[1], p[2]; return np.array([[f,0,cx],[0,f,cy],[0,0,1]])
    if model == 1: return np.array([[p[0],0,p[2]],[0,p[1],p[3]],[0,0,1]])
    return np.array([[p[0],0,p[1]],[0,p[0],p[2]],[0,0,1]])
gt = {}
for l in open(gtp):
    if l.startswith('#'): continue
    f = l.split()
    if len(f) >= 10 and f[9].endswith(('.jpg', '.png')):
        w,x,y,z = map(float, f[1:5]); t = np.array(list(map(float, f[5:8])))
        R = np.array([[1-2*(y*y+z*z),2*(x*y-z*w),2*(x*z+y*w)],[2*(x*y+z*w),1-2*(x*x+z*z),2*(y*z-x*w)],[2*(x*z-y*w),2*(y*z+x*w),1-2*(x*x+y*y)]])
        gt[f[9]] = (R, t)
lab = {}
for l in open(labp):
    f = l.strip().split(',')
    if len(f) == 4 and f[0] != 'name1':
        try: ov, ct = float(f[2]), float(f[3])
        except: continue
        L = 'M' if (ov >= .25 or ct >= .15) else ('x' if ov <= 0 and ct <= 0 else 'w')
        lab[(f[0], f[1])] = L; lab[(f[1], f[0])] = L
def tri(P1, P2, x1, x2):
    A = np.stack([x1[0]*P1[2]-P1[0], x1[1]*P1[2]-P1[1], x2[0]*P2[2]-P2[0], x2[1]*P2[2]-P2[1]])
    X = np.linalg.svd(A)[2][-1]; return X[:3]/X[3]
def decompose(E, r1, r2):
    U, S, Vt = np.linalg.svd(E)
    if np.linalg.det(U) < 0: U = -U
    if np.linalg.det(Vt) < 0: Vt = -Vt
    W = np.array([[0,-1,0],[1,0,0],[0,0,1]])
    best = None
    for R in (U@W@Vt, U@W.T@Vt):
        for t in (U[:,2], -U[:,2]):
            P1 = np.hstack([np.eye(3), np.zeros((3,1))]); P2 = np.hstack([R, t[:,None]])
            n = 0
            for a, b in zip(r1[:100], r2[:100]):
                X = tri(P1, P2, a, b)
                if X[2] > 0 and (R@X+t)[2] > 0: n += 1
            if best is None or n > best[0]: best = (n, R, t)
    return best[1], best[2]
def ang(a, b): return math.degrees(math.acos(max(-1, min(1, a@b/np.linalg.norm(a)/np.linalg.norm(b)))))
def rang(R): return math.degrees(math.acos(max(-1, min(1, (np.trace(R)-1)/2))))
rows_out = []
for pid, rows, cols, data, config, F, E in con.execute("select pair_id, rows, cols, data, config, F, E from two_view_geometries where rows >= 15 and config in (2,3,4,5,6,8)"):
    i2 = pid % 2147483647; i1 = (pid - i2) // 2147483647
    n1, c1 = imgs[i1]; n2, c2 = imgs[i2]
    m = np.frombuffer(data, np.uint32).reshape(rows, 2)
    K1, K2 = K(c1), K(c2)
    x1 = kps[i1][m[:,0]] - 0.5; x2 = kps[i2][m[:,1]] - 0.5
    h = lambda x: np.hstack([x, np.ones((len(x),1))])
    r1 = (np.linalg.inv(K1) @ h(x1).T).T; r2 = (np.linalg.inv(K2) @ h(x2).T).T
    if config == 2 and E is not None: Em = np.frombuffer(E, np.float64).reshape(3,3)
    else: Em = K2.T @ np.frombuffer(F, np.float64).reshape(3,3) @ K1
    R, t = decompose(Em, r1, r2)
    R1, t1 = gt[n1]; R2, t2 = gt[n2]
    Rg = R2 @ R1.T; tg = t2 - Rg @ t1
    rows_out.append([n1, n2, lab.get((n1, n2), 'x'), rows, config, round(rang(R.T@Rg),1), round(ang(t, tg),1), round(rang(Rg),1)])
if len(sys.argv) == 5:
    with open(sys.argv[4], 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['name1','name2','label','num_inliers','config','rotation_error','direction_error','true_rotation'])
        w.writerows(rows_out)
print('label config | pairs | median direction error | > 20 deg | max')
for L in 'Mwx':
    for c in sorted(set(r[4] for r in rows_out)):
        v = sorted(r[6] for r in rows_out if r[2] == L and r[4] == c)
        if v:
            print(f'{L} {c} | {len(v)} | {v[len(v)//2]:.1f} | {sum(x > 20 for x in v)} | {v[-1]:.1f}')
