#!/usr/bin/env python3
# Compares the cut paths (pen-down segments) of two `engraver sim --trace` CSV files: lengths,
# the farthest point of the second from the first and the farthest uncut point of the first.
# Usage: compare_cut_paths.py REFERENCE.csv OTHER.csv
import csv, math, sys
def load(p):
    rows=[r for r in csv.reader(open(p)) if r and r[0][0].isdigit()]
    return [(float(r[1]),float(r[2]),float(r[3]),int(r[4])) for r in rows]
def segs(t):
    out=[];L=0
    for a,b in zip(t,t[1:]):
        if a[3] and b[3]:
            l=math.hypot(b[0]-a[0],b[1]-a[1])
            if l>0: out.append((a[0],a[1],b[0],b[1])); L+=l
    return out,L
def dist(x,y,s):
    dx,dy=s[2]-s[0],s[3]-s[1];l2=dx*dx+dy*dy
    t=0 if l2==0 else max(0,min(1,((x-s[0])*dx+(y-s[1])*dy)/l2))
    return math.hypot(x-s[0]-t*dx,y-s[1]-t*dy)
def maxd(a,b):
    g={}
    for i,s in enumerate(b):
        for gx in range(math.floor(min(s[0],s[2])),math.floor(max(s[0],s[2]))+1):
            for gy in range(math.floor(min(s[1],s[3])),math.floor(max(s[1],s[3]))+1):
                g.setdefault((gx,gy),[]).append(s)
    w=0
    for s in a:
        for x,y in ((s[0],s[1]),(s[2],s[3])):
            best=1e9
            for ix in range(math.floor(x)-1,math.floor(x)+2):
                for iy in range(math.floor(y)-1,math.floor(y)+2):
                    for q in g.get((ix,iy),[]): best=min(best,dist(x,y,q))
            w=max(w,best)
    return w
r,lr=segs(load(sys.argv[1])); i,li=segs(load(sys.argv[2]))
print("ref cut %.4f mm, interrupted+resumed %.4f mm, diff %.4f mm; farthest off %.4f mm, uncut %.4f mm"%(lr,li,li-lr,maxd(i,r),maxd(r,i)))
