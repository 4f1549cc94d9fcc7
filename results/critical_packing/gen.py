import numpy as np, math
D = 0.024; RHO = 2500.0
NX, NY = 10, 6           # wall lattice: box Lx = 10 d, Ly = 6 d
LX, LY = NX * D, NY * D

def write_data(path, seed=1, nfx=9, nfy=5, nfz=27, az=1.1):
    """Rough walls: square lattices of touching grains (spacing d) with z jitter +-0.25 d
    (bottom around z = 0, top above the free grains); free grains on a loose lattice."""
    rng = np.random.default_rng(seed)
    atoms = []
    for i in range(NX):
        for j in range(NY):
            atoms.append((2, (i + 0.5) * D, (j + 0.5) * D, rng.uniform(-0.25, 0.25) * D))
    z0 = 1.3 * D
    for k in range(nfz):
        for i in range(nfx):
            for j in range(nfy):
                x = (i + 0.5) * LX / nfx + rng.uniform(-0.03, 0.03) * D
                y = (j + 0.5) * LY / nfy + rng.uniform(-0.03, 0.03) * D
                atoms.append((1, x, y, z0 + k * az * D))
    ztop = z0 + (nfz - 1) * az * D + 1.6 * D
    for i in range(NX):
        for j in range(NY):
            atoms.append((3, (i + 0.5) * D, (j + 0.5) * D, ztop + rng.uniform(-0.25, 0.25) * D))
    zlo, zhi = -1.5 * D, ztop + 3 * D
    with open(path, "w") as f:
        f.write("mixflow critical packing: rough-wall plane shear cell\n\n")
        f.write(f"{len(atoms)} atoms\n3 atom types\n\n")
        f.write(f"0 {LX:.10g} xlo xhi\n0 {LY:.10g} ylo yhi\n{zlo:.10g} {zhi:.10g} zlo zhi\n\nAtoms\n\n")
        for n, (t, x, y, z) in enumerate(atoms, 1):
            f.write(f"{n} {t} {D} {RHO} {x:.10g} {y:.10g} {z:.10g}\n")
    nfree = nfx * nfy * nfz
    return dict(nfree=nfree, ntop=NX * NY, nbot=NX * NY, area=LX * LY)

def rayleigh_time(E, nu=0.3, r=D / 2, rho=RHO):
    G = E / (2 * (1 + nu))
    return math.pi * r * math.sqrt(rho / G) / (0.1631 * nu + 0.8766)
