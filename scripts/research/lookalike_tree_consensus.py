#!/usr/bin/env python3
# A tree chosen by loop consensus, replayed on a look-alike filter dry run
# (docs/lookalike.md, "Tried and dropped"):
#
#   colmap gcn_pair_filter --database_path DB --dry_run 1 \
#       --PairFilter.pairs_csv_path PAIRS.csv      (hidden pairs restored)
#   scripts/research/lookalike_tree_consensus.py PAIRS.csv GT/images.txt \
#       LABELS.csv [weighted]
#
# Rebuilds the filter's tree from the CSV (backbone of mutual 4 strongest,
# maximum spanning forest), then greedily swaps a tree edge crossed by more
# failing than passing strong pairs (>= 60 inliers) for the failing pair
# that makes the most strong pairs pass (with "weighted", the largest sum of
# their distinctive inliers). Prints the strong pairs failing the loop test
# by label and the tree edges more than 30 degrees off the truth, before and
# after. LABELS.csv as in lookalike_diagnose.py.
import sys, csv, collections, numpy as np
def q2m(w,x,y,z):
    n=(w*w+x*x+y*y+z*z)**0.5; w,x,y,z=w/n,x/n,y/n,z/n
    return np.array([[1-2*(y*y+z*z),2*(x*y-z*w),2*(x*z+y*w)],[2*(x*y+z*w),1-2*(x*x+z*z),2*(y*z-x*w)],[2*(x*z-y*w),2*(y*z+x*w),1-2*(x*x+y*y)]])
def ang(R): return np.degrees(np.arccos(np.clip((np.trace(R)-1)/2,-1,1)))
gt={}
for l in open(sys.argv[2]):
    if l.startswith('#'): continue
    f=l.split()
    if len(f)>=10 and f[9].lower().endswith(('.jpg','.png')): gt[f[9]]=q2m(*map(float,f[1:5]))
labels={}
if len(sys.argv)>3:
    for l in open(sys.argv[3]):
        f=l.strip().split(',')
        if len(f)==4 and f[0]!='name1':
            try: ov=float(f[2]); ct=float(f[3])
            except: continue
            lab='matchable' if (ov>=0.25 or ct>=0.15) else ('wrong' if ov<=0 and ct<=0 else 'weak')
            labels[(f[0],f[1])]=lab; labels[(f[1],f[0])]=lab
rows=list(csv.DictReader(open(sys.argv[1])))
names=sorted(set(n for r in rows for n in (r['name1'],r['name2']))); idx={n:i for i,n in enumerate(names)}; N=len(names)
def rot(r,p): return None if r[p+'w']=='' else q2m(float(r[p+'w']),float(r[p+'x']),float(r[p+'y']),float(r[p+'z']))
E=[]
for r in rows:
    main=rot(r,'h1') if (r['config'] in ('4','5','6') and r['num_h']=='1') else rot(r,'e')
    alts=[x for x in (rot(r,'e'),rot(r,'h1'),rot(r,'h2')) if x is not None]
    a,b=idx[r['name1']],idx[r['name2']]
    g=gt[r['name2']]@gt[r['name1']].T if r['name1'] in gt and r['name2'] in gt else None
    E.append(dict(a=a,b=b,n1=r['name1'],n2=r['name2'],inl=int(r['num_inliers']),cov=int(r['covered_cells']),st=int(r['distinctive_inliers']),R=main,alts=alts,g=g,lab=labels.get((r['name1'],r['name2']),'wrong' if labels else '?'),dec=r['decision']))
order=sorted(range(len(E)),key=lambda e:(-E[e]['st'],-E[e]['cov'],-E[e]['inl'],E[e]['n1'],E[e]['n2']))
taken=[0]*N; votes=[0]*len(E)
for e in order:
    for im in (E[e]['a'],E[e]['b']):
        if taken[im]<4: taken[im]+=1; votes[e]+=1
bb=[v==2 for v in votes]
par=list(range(N))
def find(x):
    while par[x]!=x: par[x]=par[par[x]]; x=par[x]
    return x
tree=set()
for fb in (True,False):
    for e in order:
        if bb[e]!=fb or E[e]['R'] is None: continue
        a,b=find(E[e]['a']),find(E[e]['b'])
        if a==b: continue
        par[a]=b; tree.add(e)
def chain(tree):
    adj=collections.defaultdict(list)
    for e in tree: adj[E[e]['a']].append((E[e]['b'],e)); adj[E[e]['b']].append((E[e]['a'],e))
    A=[None]*N; comp=[-1]*N; parent=[(-1,-1)]*N; depth=[0]*N
    for root in range(N):
        if comp[root]>=0: continue
        comp[root]=root; A[root]=np.eye(3); q=[root]
        while q:
            i=q.pop(0)
            for j,e in adj[i]:
                if comp[j]>=0: continue
                comp[j]=root; S=E[e]['R'] if E[e]['a']==i else E[e]['R'].T
                A[j]=S@A[i]; parent[j]=(i,e); depth[j]=depth[i]+1; q.append(j)
    return A,comp,parent,depth
def err(e,A,comp):
    ed=E[e]
    if not ed['alts'] or comp[ed['a']]!=comp[ed['b']]: return -1
    C=A[ed['b']]@A[ed['a']].T
    return min(ang(R.T@C) for R in ed['alts'])
def path(i,j,parent,depth):
    p=[]
    while depth[i]>depth[j]: p.append(parent[i][1]); i=parent[i][0]
    while depth[j]>depth[i]: p.append(parent[j][1]); j=parent[j][0]
    while i!=j: p.append(parent[i][1]); i=parent[i][0]; p.append(parent[j][1]); j=parent[j][0]
    return p
strong=[e for e in range(len(E)) if E[e]['inl']>=60]
def score(tree):
    A,comp,parent,depth=chain(tree)
    res={}
    for e in strong:
        if e in tree: continue
        x=err(e,A,comp)
        if x>=0: res[e]=x<=30
    return res,(A,comp,parent,depth)
def report(tree,tag):
    res,(A,comp,parent,depth)=score(tree)
    fails=[e for e,ok in res.items() if not ok]
    bad=[e for e in tree if E[e]['g'] is not None and ang(E[e]['R'].T@E[e]['g'])>30]
    # chained vs gt error over all images in the same comp: rel to first
    fl=collections.Counter(E[e]['lab'] for e in fails)
    print(tag,"strong non-tree:",len(res),"fail:",len(fails),dict(fl),"| tree edges >30deg off GT:",[(E[e]['n1'],E[e]['n2'],E[e]['lab'],E[e]['inl'],E[e]['st']) for e in bad])
report(tree,"before")
WEIGHTED=len(sys.argv)>4 and sys.argv[4]=='weighted'
def total(res): return sum((E[e]['st'] if WEIGHTED else 1) for e,ok in res.items() if ok)
for it in range(20):
    res,(A,comp,parent,depth)=score(tree)
    cross=collections.defaultdict(lambda:[0,0])
    for e,ok in res.items():
        for t in path(E[e]['a'],E[e]['b'],parent,depth): cross[t][0 if ok else 1]+=1
    cands=sorted([t for t in tree if cross[t][1]>cross[t][0]],key=lambda t:-(cross[t][1]-cross[t][0]))
    base=total(res); best=None
    for t in cands[:5]:
        # replacement candidates: failing strong pairs whose path crosses t
        for c in [e for e,ok in res.items() if not ok and t in path(E[e]['a'],E[e]['b'],parent,depth) and E[e]['R'] is not None]:
            nt=(tree-{t})|{c}; r2,_=score(nt); s=total(r2)
            if best is None or s>best[0]: best=(s,t,c)
    if best is None or best[0]<=base: break
    print(" swap out",E[best[1]]['n1'],E[best[1]]['n2'],E[best[1]]['lab'],"in",E[best[2]]['n1'],E[best[2]]['n2'],E[best[2]]['lab'],"passes",base,"->",best[0])
    tree=(tree-{best[1]})|{best[2]}
report(tree,"after ")
