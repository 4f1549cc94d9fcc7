"""Two-body model of the implicit drag's exchange: what the fluid step's implicit term does to the
mixture's momentum with `implicitDragDefect kept` and `returned` (coupling/README.md).

A fluid mass mf and a grain of mass mp, drag coefficient beta (m/beta = 8e-6 s, the packed HB
column's relaxation time), forces Ff and Fp, DEM step 1.24e-5 s. Each exchange: the grain runs
`every` DEM steps by backward Euler with the fluid velocity held; the fluid step takes the grain's
impulse explicitly and beta_T = beta / (1 + beta T / mp) implicitly, and with `returned` adds the
last step's beta_T (U_new - U_held) back. Prints the mixture momentum after 0.05 s against the
impulse of the forces (1 = conserved).
Usage: python3 results/convergence/two_body_defect.py
"""


def run(returned, every, mf=0.4, mp=1.5, relax=8e-6, Ff=0.4 * 9.81, Fp=1.5 * 9.81 * 0.6,
        dt=1.24e-5, end=0.05):
    beta = mp / relax
    T = dt * every
    bT = beta / (1 + beta * T / mp)
    U = v = back = t = 0.0
    while t < end - 1e-12:
        J = 0.0
        for _ in range(every):
            vn = (mp * v + dt * (Fp + beta * U)) / (mp + beta * dt)
            J += beta * (U - vn) * dt
            v = vn
        U1 = (mf * U + T * (Ff - J / T + bT * U + back)) / (mf + bT * T)
        back = bT * (U1 - U) if returned else 0.0
        U = U1
        t += T
    return (mf * U + mp * v) / ((Ff + Fp) * t)


if __name__ == "__main__":
    print("exchangeEvery  kept  returned  (mixture momentum / force impulse)")
    for every in (1, 2, 4, 10, 25, 100):
        print(f"{every:13d}  {run(False, every):.4f}  {run(True, every):.4f}")
