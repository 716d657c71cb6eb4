#!/usr/bin/python3
"""Top view of a run's map/mesh.ply, for the docs: its RGB vertex colours
and its height, side by side (Debian's python3-numpy and python3-matplotlib).

    scripts/render_mesh_topview.py RUN/map/mesh.ply OUT.png
"""
import sys

import numpy as np
import matplotlib; matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection


def read_ply(path):
    with open(path,'rb') as f:
        header=[]; 
        while True:
            line=f.readline().decode().strip(); header.append(line)
            if line=='end_header': break
        nv=int([l for l in header if l.startswith('element vertex')][0].split()[2])
        nf=int([l for l in header if l.startswith('element face')][0].split()[2])
        props=[l.split()[1:] for l in header if l.startswith('property') and 'list' not in l]
        dt=[]
        for t,n in props:
            dt.append((n,{'double':'<f8','float':'<f4','uchar':'u1','int':'<i4'}[t]))
        v=np.frombuffer(f.read(nv*np.dtype(dt).itemsize),dtype=dt,count=nv)
        faces=np.frombuffer(f.read(nf*13),dtype=[('n','u1'),('i','<i4',3)],count=nf)['i']
    return v, faces
v,f=read_ply(sys.argv[1])
xy=np.stack([v['y'],v['x']],1)  # east, north
tri=xy[f]
have_col='red' in v.dtype.names
fig,ax=plt.subplots(1,2,figsize=(12,7))
if have_col:
    c=np.stack([v['red'],v['green'],v['blue']],1)/255.0
    fc=c[f].mean(1)
    ax[0].add_collection(PolyCollection(tri,facecolors=fc,edgecolors='none'))
ax[0].set_title('map/mesh.ply: RGB vertex colours (top view)')
z=v['z']; fz=z[f].mean(1)
ax[1].add_collection(PolyCollection(tri,array=-fz,cmap='terrain',edgecolors='none'))
ax[1].set_title('map/mesh.ply: height (up = -down, m)')
for a in ax:
    a.set_xlim(xy[:,0].min(),xy[:,0].max()); a.set_ylim(xy[:,1].min(),xy[:,1].max()); a.set_aspect('equal'); a.set_xlabel('east (m)'); a.set_ylabel('north (m)')
plt.tight_layout(); plt.savefig(sys.argv[2],dpi=90)
