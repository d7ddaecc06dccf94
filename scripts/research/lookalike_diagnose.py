#!/usr/bin/env python3
# The look-alike filter's evidence against the truth (docs/lookalike.md,
# "How it decides", "Where it fails"):
#
#   colmap gcn_pair_filter --database_path DB --dry_run 1 \
#       --PairFilter.pairs_csv_path PAIRS.csv
#   scripts/research/lookalike_diagnose.py PAIRS.csv GT/images.txt [LABELS.csv]
#
# Per COLMAP configuration: how far the rotation from E (or F) and the best
# and worst of the homography's decompositions lie from the true relative
# rotation; the tree edges whose rotation is wrong; and per rejected pair
# whether its own rotation or the rotation chained along the tree is wrong;
# the view parallax of matchable pairs and of pairs whose true rotation is
# over 135 degrees (on an object ring, look-alikes), by strength.
# LABELS.csv is gcn_benchmark's labels/labels.csv: "matchable" as the
# benchmark counts it (overlap >= 0.25 or common-track ratio >= 0.15),
# "wrong" for pairs it does not list (nothing shared), "weak" otherwise.
import sys, math, csv, collections
def qmat(w,x,y,z):
    n=math.sqrt(w*w+x*x+y*y+z*z); w,x,y,z=w/n,x/n,y/n,z/n
    return [[1-2*(y*y+z*z),2*(x*y-z*w),2*(x*z+y*w)],[2*(x*y+z*w),1-2*(x*x+z*z),2*(y*z-x*w)],[2*(x*z-y*w),2*(y*z+x*w),1-2*(x*x+y*y)]]
def mul(a,b): return [[sum(a[i][k]*b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
def tr(a): return [[a[j][i] for j in range(3)] for i in range(3)]
def ang(a): return math.degrees(math.acos(max(-1,min(1,(a[0][0]+a[1][1]+a[2][2]-1)/2))))
def err(A,B): return ang(mul(tr(A),B))
gt={}
for l in open(sys.argv[2]):
    if l.startswith('#'): continue
    f=l.split()
    if len(f)>=10 and f[9].endswith(('.jpg','.png','.JPG')):
        gt[f[9]]=qmat(*map(float,f[1:5]))
labels={}
if len(sys.argv)>3:
    for l in open(sys.argv[3]):
        f=l.strip().split(',')
        if len(f)==4 and f[0]!='name1':
            try:
                ov=float(f[2]); ct=float(f[3])
            except: continue
            lab='matchable' if (ov>=0.25 or ct>=0.15) else ('wrong' if ov<=0 and ct<=0 else 'weak')
            labels[(f[0],f[1])]=lab; labels[(f[1],f[0])]=lab
rows=list(csv.DictReader(open(sys.argv[1])))
def rot(r,p):
    if r[p+'w']=='' : return None
    return qmat(float(r[p+'w']),float(r[p+'x']),float(r[p+'y']),float(r[p+'z']))
# the rotation the tree chains (AssignRotations in pair_filter.cc)
def tree_rot(r):
    return rot(r,'h1') if (r['config'] in ('4','5','6') and r['num_h']=='1') else rot(r,'e')
# tree chaining
adj=collections.defaultdict(list)
for r in rows:
    if r['in_tree']=='1':
        R=tree_rot(r); adj[r['name1']].append((r['name2'],R)); adj[r['name2']].append((r['name1'],tr(R)))
absr={}; comp={}
for root in sorted(set(n for r in rows for n in (r['name1'],r['name2']))):
    if root in absr: continue
    absr[root]=[[1,0,0],[0,1,0],[0,0,1]]; comp[root]=root; q=[root]
    while q:
        a=q.pop(0)
        for b,R in adj[a]:
            if b in absr: continue
            absr[b]=mul(R,absr[a]); comp[b]=root; q.append(b)
stats=collections.defaultdict(list)
out=[]
for r in rows:
    a,b=r['name1'],r['name2']
    if a not in gt or b not in gt: continue
    G=mul(gt[b],tr(gt[a]))
    E=rot(r,'e'); eE=err(E,G) if E else -1
    hs=[rot(r,'h1'),rot(r,'h2')]; hs=[h for h in hs if h]
    eH=[err(h,G) for h in hs]
    chained=mul(absr[b],tr(absr[a])) if comp[a]==comp[b] else None
    eC=err(chained,G) if chained else -1
    lab=labels.get((a,b),'wrong' if labels else '?')
    stats[r['config']].append((eE,min(eH) if eH else -1,max(eH) if eH else -1,int(r['num_h'])))
    T=tree_rot(r); eT=err(T,G) if T else -1
    out.append((r['decision'],r['config'],a,b,r['num_inliers'],r['covered_cells'],float(r['rotation_error']),eE,eH,eC,r['in_tree'],lab,eT,float(r.get('view_parallax',-1)),ang(G)))
def med(v):
    v=sorted(x for x in v if x>=0); return v[len(v)//2] if v else float('nan')
print("config count | median err E/F vs GT | #E/F>10deg | median best-H | #bestH>10 | median worst-H | num_h dist | #no rotation within 30deg of GT")
for c,v in sorted(stats.items()):
    print(c,len(v),"| %.2f | %d | %.2f | %d | %.2f |"%(med([x[0] for x in v]),sum(x[0]>10 or x[0]<0 for x in v),med([x[1] for x in v]),sum(x[1]>10 or x[1]<0 for x in v),med([x[2] for x in v])),dict(collections.Counter(x[3] for x in v)),"|",sum(min([e for e in (x[0],x[1]) if e>=0] or [999])>30 for x in v))
print("among pairs some rotation of which lies within 30deg of GT (real geometry):")
for c,v in sorted(stats.items()):
    v=[x for x in v if min([e for e in (x[0],x[1]) if e>=0] or [999])<=30]
    print(" config",c,len(v),"| median E/F %.2f, #E/F>30deg %d | median best-H %.2f, #bestH>30deg %d"%(med([x[0] for x in v]),sum(x[0]>30 or x[0]<0 for x in v),med([x[1] for x in v]),sum(x[1]>30 or x[1]<0 for x in v)))
far=[int(o[5]) for o in out if min([e for e in [o[7]]+o[8] if e>=0] or [0])>90]
near=[int(o[5]) for o in out if min([e for e in [o[7]]+o[8] if e>=0] or [0])<=90]
print("covered cells: %d pairs whose every rotation is >90deg off GT, median %s; %d others, median %s"%(len(far),sorted(far)[len(far)//2] if far else '-',len(near),sorted(near)[len(near)//2] if near else '-'))
tree=[o for o in out if o[10]=='1']
print("tree edges:",len(tree),"whose chained rotation is >10deg off GT:",sum(o[12]>10 for o in tree),[ (o[2],o[3],'config',o[1],round(o[12],1),o[11]) for o in tree if o[12]>10])
print("rejected:")
for o in out:
    if o[0]!='kept':
        print(" %s %s cfg%s inl %s cells %s | loop err %.1f | E/F vs GT %.1f | H vs GT %s | chained vs GT %.1f | %s"%(o[2],o[3],o[1],o[4],o[5],o[6],o[7],[round(x,1) for x in o[8]],o[9],o[11]))
rej=[o for o in out if o[0]!='kept']
print("rejected %d: matchable %d wrong %d; pair wrong (E/F>15) %d, chain wrong(>15) %d"%(len(rej),sum(o[11]=='matchable' for o in rej),sum(o[11]=='wrong' for o in rej),sum(o[7]>15 for o in rej),sum(o[9]>15 for o in rej)))
# The parallax test: per pair strength and true viewpoint change, the
# measured view parallax (outside the tree, where it is defined).
print("view parallax (pairs outside the tree): group | pairs | max parallax | rejected by view_parallax")
for name,sel in (("matchable, >= 60 inliers",lambda o:o[11]=='matchable' and int(o[4])>=60),
                 ("matchable, < 60 inliers",lambda o:o[11]=='matchable' and int(o[4])<60),
                 ("true rotation > 135deg, < 60 inliers",lambda o:o[14]>135 and int(o[4])<60),
                 ("true rotation > 135deg, >= 60 inliers",lambda o:o[14]>135 and int(o[4])>=60)):
    v=[o for o in out if o[10]=='0' and o[13]>=0 and sel(o)]
    print(" %s | %d | %s | %d"%(name,len(v),"%.1f"%max(o[13] for o in v) if v else '-',sum(o[0]=='view_parallax' for o in v)))
kept_far=[o for o in out if o[0]=='kept' and o[14]>135]
print("kept with true rotation > 135deg: %d (%s)"%(len(kept_far),", ".join("%s-%s %s inl"%(o[2],o[3],o[4]) for o in kept_far)))
print("rejected by reason and label:", dict(sorted(collections.Counter((o[0], o[11]) for o in rej).items())))
