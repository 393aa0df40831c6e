#!/usr/bin/env python3
"""Reference values: plate on a Winkler foundation, half-plane x >= 0, free edge
at x = 0, uniform rectangular patch q0 on [c, c+a] x [-b, b] (c = 0: edge load).

Kirchhoff and Reissner-Mindlin theories.  Fourier transform in y (cos/sin
transform), exact solution of the ODE system in x (piecewise: particular +
exponentials), numerical inversion  f(x,y) = (1/pi) int_0^inf f^(x,xi) cos(xi y) dxi.

mpmath only.  Run:  python3 edge_load_reference.py [--quick] [--superfine]   (~10 / ~17 min)
Units: kN, m, kPa.  w positive downward; M_x = -D(w,xx + nu w,yy) (Kirchhoff),
M_x = -D(bx,x + nu by,y) (Mindlin): positive = tension at the bottom face.
"""
import sys
import time
import mpmath as mp

mp.mp.dps = 30

# ----------------------------------------------------------------- data
E = mp.mpf(3e7)
NU = mp.mpf('0.15')
T = mp.mpf('0.25')
K = mp.mpf(5e4)
Q0 = mp.mpf(700)
A = mp.mpf('0.3')
B = mp.mpf('0.15')
D0 = E * T**3 / (12 * (1 - NU**2))
G = E / (2 * (1 + NU))
DS0 = mp.mpf(5) / 6 * G * T
L = (D0 / K) ** mp.mpf('0.25')


class Plate:
    def __init__(self, theory, D=D0, Ds=DS0, nu=NU, k=K):
        self.theory, self.D, self.Ds, self.nu, self.k = theory, D, Ds, nu, k
        self.m = 2 if theory == 'kirchhoff' else 3      # decaying roots
        self.n = 2 * self.m                              # state size

    # ---- roots p = s^2 - xi^2 of the bending/foundation factor
    def pvals(self):
        D, k = self.D, self.k
        if self.theory == 'kirchhoff':              # D p^2 + k = 0
            r = mp.sqrt(k / D) * 1j
            return [r, -r]
        c = k * D / self.Ds                          # D p^2 - c p + k = 0
        disc = mp.sqrt(mp.mpc(c * c - 4 * D * k))
        return [(c + disc) / (2 * D), (c - disc) / (2 * D)]

    def modes(self, xi):
        """list of (s, vec(lam)) with Re s > 0; vec(lam) = state at x_ref of
        the mode exp(lam (x - x_ref)), lam = +-s."""
        out = []
        D, Ds = self.D, self.Ds
        for p in self.pvals():
            s = mp.sqrt(xi * xi + p)
            if self.theory == 'kirchhoff':
                out.append((s, lambda lam: [1, lam, lam**2, lam**3]))
            else:
                # irrotational (bending) mode: beta = grad phi, w = phi - (D/Ds) Lap phi
                W0 = 1 - D / Ds * p
                out.append((s, (lambda W0: lambda lam:
                                [W0, lam * W0, lam, lam * lam, -xi, -lam * xi])(W0)))
        if self.theory == 'mindlin':
            # rotational (shear boundary-layer) mode: beta = curl psi, w = 0
            s3 = mp.sqrt(xi * xi + 2 * Ds / ((1 - self.nu) * D))
            out.append((s3, lambda lam: [0, 0, xi, lam * xi, -lam, -lam * lam]))
        return out

    def particular(self, xi):
        """state of the x-independent solution for unit load q^ = 1"""
        D, Ds, k = self.D, self.Ds, self.k
        if self.theory == 'kirchhoff':
            return [1 / (D * xi**4 + k), 0, 0, 0]
        phi = 1 / (D * xi**4 + k + k * D * xi**2 / Ds)
        return [phi * (1 + D * xi**2 / Ds), 0, 0, 0, -xi * phi, 0]

    def bc_rows(self, xi):
        nu = self.nu
        if self.theory == 'kirchhoff':   # M_x = 0, V_x = 0   (state W,W',W'',W''')
            return [[-nu * xi**2, 0, 1, 0], [0, -(2 - nu) * xi**2, 0, 1]]
        # state (W, W', X, X', Y, Y'):  M_x=0: X'+nu xi Y; M_xy=0: Y'-xi X; Q_x=0: W'-X
        return [[0, 0, 0, 1, nu * xi, 0], [0, 0, -xi, 0, 0, 1], [0, 1, -1, 0, 0, 0]]

    def resultants(self, S, xi):
        """(w, M_x, M_y) transforms (cos-type) from state S"""
        D, nu = self.D, self.nu
        if self.theory == 'kirchhoff':
            return S[0], -D * (S[2] - nu * xi**2 * S[0]), -D * (-xi**2 * S[0] + nu * S[2])
        return S[0], -D * (S[3] + nu * xi * S[4]), -D * (xi * S[4] + nu * S[3])

    def ode_residual(self, xi, lam, v, rhs=0):
        """residual of the Fourier-space field equations for exp(lam x) * v"""
        D, Ds, k, nu = self.D, self.Ds, self.k, self.nu
        if self.theory == 'kirchhoff':
            return [D * (lam**2 - xi**2)**2 * v[0] + k * v[0] - rhs]
        W, X, Y = v[0], v[2], v[4]
        r1 = Ds * ((lam**2 - xi**2) * W - lam * X - xi * Y) - k * W + rhs
        r2 = D * (lam**2 * X - (1 - nu) / 2 * xi**2 * X + (1 + nu) / 2 * xi * lam * Y) \
            + Ds * (lam * W - X)
        r3 = D * (-xi**2 * Y + (1 - nu) / 2 * lam**2 * Y - (1 + nu) / 2 * xi * lam * X) \
            + Ds * (-xi * W - Y)
        return [r1, r2, r3]


def solve_xi(pl, xi, c, a, xs, want_integral=False):
    """Response to q^ = 1 on c < x < c+a.  Returns list of (w, Mx, My) at xs
    (and optionally int_0^inf W dx)."""
    md = pl.modes(xi)
    m, n = pl.m, pl.n
    brk = ([mp.mpf(0)] if c > 0 else []) + [mp.mpf(c), mp.mpf(c + a)]
    # regions: [brk[i], brk[i+1]] finite, last [brk[-1], inf)
    regs = []
    for i in range(len(brk) - 1):
        loaded = (brk[i] >= c and brk[i + 1] <= c + a)
        regs.append((brk[i], brk[i + 1], loaded))
    regs.append((brk[-1], None, False))
    part = pl.particular(xi)
    zero = [0] * n
    # unknown layout: finite region: m left modes (lam=-s, ref x0), m right modes (lam=+s, ref x1)
    offs, nunk = [], 0
    for (x0, x1, ld) in regs:
        offs.append(nunk)
        nunk += 2 * m if x1 is not None else m

    def region_state_cols(ir, x):
        """columns (list of state vectors) of region ir evaluated at x, and particular"""
        x0, x1, ld = regs[ir]
        cols = []
        for (s, vec) in md:
            e = mp.exp(-s * (x - x0))
            cols.append([e * v for v in vec(-s)])
        if x1 is not None:
            for (s, vec) in md:
                e = mp.exp(s * (x - x1))
                cols.append([e * v for v in vec(s)])
        return cols, (part if ld else zero)

    M = mp.matrix(nunk, nunk)
    rhs = mp.matrix(nunk, 1)
    row = 0
    cols, pp = region_state_cols(0, mp.mpf(0))
    for bcr in pl.bc_rows(xi):
        for j, col in enumerate(cols):
            M[row, offs[0] + j] = sum(bcr[i] * col[i] for i in range(n))
        rhs[row] = -sum(bcr[i] * pp[i] for i in range(n))
        row += 1
    for ir in range(len(regs) - 1):
        xb = regs[ir][1]
        cl, pl_ = region_state_cols(ir, xb)
        cr, pr_ = region_state_cols(ir + 1, xb)
        for i in range(n):
            for j, col in enumerate(cl):
                M[row, offs[ir] + j] = col[i]
            for j, col in enumerate(cr):
                M[row, offs[ir + 1] + j] = -col[i]
            rhs[row] = pr_[i] - pl_[i]
            row += 1
    coef = mp.lu_solve(M, rhs)

    def state_at(x):
        for ir, (x0, x1, ld) in enumerate(regs):
            if x1 is None or x <= x1:
                break
        cols, pp = region_state_cols(ir, x)
        S = [pp[i] + sum(coef[offs[ir] + j] * cols[j][i] for j in range(len(cols)))
             for i in range(n)]
        return S
    res = [pl.resultants(state_at(mp.mpf(x)), xi) for x in xs]
    if not want_integral:
        return res
    tot = 0
    for ir, (x0, x1, ld) in enumerate(regs):
        for j, (s, vec) in enumerate(md):
            W0 = vec(-s)[0]
            if x1 is None:
                tot += coef[offs[ir] + j] * W0 / s
            else:
                f = (1 - mp.exp(-s * (x1 - x0))) / s
                tot += coef[offs[ir] + j] * W0 * f
                tot += coef[offs[ir] + m + j] * vec(s)[0] * f
        if ld:
            tot += part[0] * (x1 - x0)
    return res, tot


# ----------------------------------------------------------------- quadrature
_GL = {}


def gauss_legendre(n):
    if n in _GL:
        return _GL[n]
    nodes = []
    for i in range(1, n + 1):
        x = mp.cos(mp.pi * (i - mp.mpf(1) / 4) / (n + mp.mpf(1) / 2))
        for _ in range(100):
            p0, p1 = mp.mpf(1), x
            for kk in range(2, n + 1):
                p0, p1 = p1, ((2 * kk - 1) * x * p1 - (kk - 1) * p0) / kk
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < mp.mpf(10) ** (-mp.mp.dps + 3):
                break
        nodes.append((x, 2 / ((1 - x * x) * dp * dp)))
    _GL[n] = nodes
    return nodes


def gl_panel(f, lo, hi, n):
    h = (hi - lo) / 2
    mid = (hi + lo) / 2
    acc = None
    for (x, wt) in gauss_legendre(n):
        v = f(mid + h * x)
        acc = [wt * h * vi for vi in v] if acc is None else [a_ + wt * h * vi for a_, vi in zip(acc, v)]
    return acc


def int_sin_over_xi(F, omega, opts):
    """vector  int_0^inf F(xi) sin(omega xi)/xi dxi, F smooth, algebraic decay.
    Fine panels on [0, Z0], then half periods between zeros of sin, partial sums
    accelerated by repeated averaging (Euler transform)."""
    omega = mp.mpf(omega)
    sgn = 1 if omega > 0 else -1
    om = abs(omega)
    hp = mp.pi / om
    n0 = int(mp.ceil(opts['xi_fine'] / hp))
    Z0 = n0 * hp
    npan = int(mp.ceil(Z0 / opts['h_fine']))

    def g(xi):
        f = mp.sin(om * xi) / xi
        return [f * v for v in F(xi)]
    tot = None
    for i in range(npan):
        v = gl_panel(g, Z0 * i / npan, Z0 * (i + 1) / npan, opts['n_gl'])
        tot = v if tot is None else [p + q for p, q in zip(tot, v)]
    nsub = max(1, int(mp.ceil(hp / opts['h_tail'])))
    nhalf = max(int(mp.ceil((opts['xi_max'] - Z0) / hp)), opts['euler'] + 2)
    partial = []
    for j in range(nhalf):
        lo = Z0 + j * hp
        for i in range(nsub):
            v = gl_panel(g, lo + hp * i / nsub, lo + hp * (i + 1) / nsub, opts['n_gl'])
            tot = [p + q for p, q in zip(tot, v)]
        partial.append(tot)
    seq = partial[-(opts['euler'] + 1):]
    while len(seq) > 1:
        seq = [[(p + q) / 2 for p, q in zip(s1, s2)] for s1, s2 in zip(seq[:-1], seq[1:])]
    return [sgn * v for v in seq[0]], [sgn * v for v in partial[-1]]


def edge_reference(pl, opts, c=0, ypt=mp.mpf('0.5')):
    """returns dict of physical values"""
    a = A
    xs0 = [mp.mpf(0), a / 2, mp.mpf(1)]
    cache = {}

    def Gy0(xi):          # y = 0 outputs: w(0),w(a/2),w(1),My(0),Mx(a/2)
        r = solve_xi(pl, xi, c, a, xs0)
        return [r[0][0].real, r[1][0].real, r[2][0].real, r[0][2].real, r[1][1].real]
    I0, I0raw = int_sin_over_xi(Gy0, B, opts)
    f = 2 * Q0 / mp.pi
    names = ['w(0,0)', 'w(a/2,0)', 'w(1,0)', 'My(0,0)', 'Mx(a/2,0)']
    out = {nm: f * v for nm, v in zip(names, I0)}
    out['_raw'] = {nm: f * v for nm, v in zip(names, I0raw)}

    def Gw0(xi):
        return [solve_xi(pl, xi, c, a, [0])[0][0].real]
    # sin(xi b) cos(xi y) = (sin((b+y)xi) + sin((b-y)xi))/2
    Ip, _ = int_sin_over_xi(Gw0, B + ypt, opts)
    Im, _ = int_sin_over_xi(Gw0, B - ypt, opts)
    out['w(0,0.5)'] = Q0 / mp.pi * (Ip[0] + Im[0])
    return out


# ----------------------------------------------------------------- checks
def equilibrium(pl, c=0):
    (_, tot) = solve_xi(pl, mp.mpf(0), c, A, [0], want_integral=True)
    qhat0 = 2 * B * Q0
    return K * qhat0 * tot.real, Q0 * A * 2 * B


def mode_residuals(pl, xi):
    mx = 0
    for (s, vec) in pl.modes(xi):
        for lam in (s, -s):
            v = vec(lam)
            r = pl.ode_residual(xi, lam, v)
            mx = max(mx, max(abs(x) for x in r) / (pl.D * abs(lam)**4 + pl.k))
    pp = pl.particular(xi)
    r = pl.ode_residual(xi, 0, pp, rhs=1)
    mx = max(mx, max(abs(x) for x in r))
    return mx


def infinite_plate_center(pl):
    """w, Mx, My at the centre of the patch (a x 2b) on an infinite plate:
    2D Fourier integral, inner alpha-integral in closed form by partial fractions."""
    D, Ds, k, nu = pl.D, pl.Ds, pl.k, pl.nu
    Ah = A / 2
    if pl.theory == 'kirchhoff':
        r = [mp.sqrt(k / D) * 1j, -mp.sqrt(k / D) * 1j]        # D u^2 + k = 0
        Nw = lambda u: 1
    else:
        # w^ = q^ (1 + D u/Ds)/(D u^2 + k D u/Ds + k),  phi^ = q^/(same)
        cc = k * D / Ds
        disc = mp.sqrt(mp.mpc(cc * cc - 4 * D * k))
        r = [(-cc + disc) / (2 * D), (-cc - disc) / (2 * D)]
        Nw = lambda u: 1 + D * u / Ds
    # H(u) = N(u)/(D (u-r1)(u-r2)) = (1/D) sum c_j/(u - r_j);  u - r = alpha^2 + m^2
    def coefs(N):
        return [N(r[0]) / (r[0] - r[1]), N(r[1]) / (r[1] - r[0])]
    cw, cp = coefs(Nw), coefs(lambda u: 1)

    def inner(beta):
        # int_0^inf 2 sin(aA)/a * H da = (pi/D) sum c (1-e^{-mA})/m^2
        # int_0^inf 2 sin(aA)/a * a^2 H da = (pi/D) sum c e^{-mA}   (for c with N deg<=1 ok)
        w_ = 0; a2 = 0; b0 = 0
        for j in range(2):
            m = mp.sqrt(beta * beta - r[j])
            w_ += cw[j] * (1 - mp.exp(-m * Ah)) / m**2
            b0 += cp[j] * (1 - mp.exp(-m * Ah)) / m**2
            a2 += cp[j] * mp.exp(-m * Ah)
        w_ *= mp.pi / D; b0 *= mp.pi / D; a2 *= mp.pi / D
        # moments: Kirchhoff M^ = D(beta^2 + nu alpha^2) w^ ; Mindlin uses phi^ (cp)
        mx = D * (a2 + nu * beta**2 * b0)
        my = D * (beta**2 * b0 + nu * a2)
        return [w_.real, mx.real, my.real]
    f = Q0 / mp.pi**2 * 2
    res = [0, 0, 0]
    # outer: int_0^inf (sin(beta b)/beta) inner(beta) dbeta ; w decays fast, moments ~beta^-3
    opts = dict(xi_fine=60, h_fine=mp.mpf('0.5'), h_tail=mp.mpf(4), n_gl=24, xi_max=1500, euler=16)
    I, _ = int_sin_over_xi(inner, B, opts)
    return [f * v for v in I]


def westergaard(P, h, a_s, l, nu, E, k):
    """Ioannides, Thompson & Barenberg (1985) edge formulas (semicircular load of
    radius a_s, centre on the edge) and Westergaard (1926) original edge formulas."""
    c = 3 * (1 + nu) * P / (mp.pi * (3 + nu) * h**2)
    sig_semi = c * (mp.log(E * h**3 / (100 * k * a_s**4)) + mp.mpf('3.84') - 4 * nu / 3
                    + (1 + 2 * nu) * a_s / (2 * l))
    w_semi = mp.sqrt(2 + mp.mpf('1.2') * nu) * P / mp.sqrt(E * h**3 * k) \
        * (1 - (mp.mpf('0.323') + mp.mpf('0.17') * nu) * a_s / l)
    return sig_semi, w_semi


def edge_point_load_coefficient():
    """Kirchhoff, point load P at the free edge: w(0,0) sqrt(E h^3 k)/P (exact,
    via a 1e-5 m wide line-load strip), to check the sqrt(2+1.2 nu) leading term."""
    pl = Plate('kirchhoff')
    eps = mp.mpf('1e-5')
    g = lambda xi: solve_xi(pl, xi, 0, eps, [0])[0][0].real / eps
    I = mp.quad(g, [0, 1, 3, 10, 30, 100, 300, 1000, 3000])
    I += g(mp.mpf(3000)) * 3000 / 2             # tail ~ C xi^-3
    return I / mp.pi * mp.sqrt(E * T**3 * K)


def main():
    quick = '--quick' in sys.argv
    t0 = time.time()
    print('D = %s  Ds = %s  l = %s  P = %s' % (mp.nstr(D0, 12), mp.nstr(DS0, 12),
                                             mp.nstr(L, 12), mp.nstr(Q0 * A * 2 * B, 8)))
    kir, mind = Plate('kirchhoff'), Plate('mindlin')
    for pl in (kir, mind):
        print(pl.theory, 'max mode residual', mp.nstr(max(mode_residuals(pl, mp.mpf(x))
                                                           for x in ('0', '0.7', '13', '250')), 3))
        lhs, rhs = equilibrium(pl)
        print(pl.theory, 'equilibrium k*int w = %s  load = %s  rel.err %s' %
              (mp.nstr(lhs, 15), mp.nstr(rhs, 15), mp.nstr(lhs / rhs - 1, 3)))
    coarse = dict(xi_fine=40, h_fine=mp.mpf(1), h_tail=mp.mpf(8), n_gl=16, xi_max=250, euler=8)
    fine = dict(xi_fine=60, h_fine=mp.mpf('0.5'), h_tail=mp.mpf(4), n_gl=24, xi_max=600, euler=12)
    superfine = dict(xi_fine=60, h_fine=mp.mpf('0.5'), h_tail=mp.mpf(4), n_gl=24, xi_max=1500,
                     euler=16)
    levels = [('coarse', coarse), ('fine', fine)]
    if '--superfine' in sys.argv:
        levels.append(('superfine', superfine))
    results = {}
    for pl in (kir, mind):
        for tag, opts in levels:
            if quick and tag == 'fine':
                continue
            r = edge_reference(pl, opts)
            results[(pl.theory, tag)] = r
            print('\n%s [%s] (%.0f s)' % (pl.theory, tag, time.time() - t0))
            for nm in ['w(0,0)', 'w(a/2,0)', 'w(0,0.5)', 'w(1,0)', 'My(0,0)', 'Mx(a/2,0)']:
                extra = ''
                if nm == 'My(0,0)':
                    extra = '   sigma_y = 6M/t^2 = %s kPa' % mp.nstr(6 * r[nm] / T**2, 10)
                print('  %-10s %s%s' % (nm, mp.nstr(r[nm], 12), extra))
            print('  (un-extrapolated partial sums:',
                  ', '.join('%s=%s' % (k_, mp.nstr(v, 10)) for k_, v in r['_raw'].items()), ')')
    if not quick:
        print('\nquadrature convergence (coarse vs fine, relative):')
        for th in ('kirchhoff', 'mindlin'):
            c_, f_ = results[(th, 'coarse')], results[(th, 'fine')]
            print(' ', th, ', '.join('%s %s' % (nm, mp.nstr(abs(c_[nm] / f_[nm] - 1), 2))
                                       for nm in c_ if nm != '_raw'))
            if (th, 'superfine') in results:
                s_ = results[(th, 'superfine')]
                print(' ', th, 'fine vs superfine:',
                      ', '.join('%s %s' % (nm, mp.nstr(abs(f_[nm] / s_[nm] - 1), 2))
                                for nm in f_ if nm != '_raw'))
    # Mindlin -> Kirchhoff: D fixed, Ds -> inf
    print('\nMindlin with Ds*f (D fixed) -> Kirchhoff:')
    for fac in (1, 100, 10000, 1000000):
        pl = Plate('mindlin', Ds=DS0 * fac)
        r = edge_reference(pl, coarse)
        print('  f=%-8g w(0,0)=%s  w(a/2,0)=%s  My(0,0)=%s  Mx(a/2,0)=%s' % (
            fac, mp.nstr(r['w(0,0)'], 10), mp.nstr(r['w(a/2,0)'], 10),
            mp.nstr(r['My(0,0)'], 10), mp.nstr(r['Mx(a/2,0)'], 10)))
    # far-from-edge check: patch moved to c = 30 m vs infinite plate 2D integral
    print('\nPatch at x in [30, 30.3] (centre) vs infinite plate (2D Fourier):')
    for th in ('kirchhoff', 'mindlin'):
        pl = Plate(th)
        xc = 30 + A / 2
        opts = fine

        def Gc(xi, pl=pl):
            r = solve_xi(pl, xi, mp.mpf(30), A, [xc])[0]
            return [r[0].real, r[1].real, r[2].real]
        I, _ = int_sin_over_xi(Gc, B, opts)
        hp = [2 * Q0 / mp.pi * v for v in I]
        inf = infinite_plate_center(pl)
        print('  %-9s half-plane w,Mx,My = %s ; infinite = %s ; rel.diff %s' % (
            th, [mp.nstr(v, 10) for v in hp], [mp.nstr(v, 10) for v in inf],
            [mp.nstr(abs(u / v - 1), 2) for u, v in zip(hp, inf)]))
    # Westergaard / Ioannides
    P = Q0 * A * 2 * B
    a_s = mp.sqrt(2 * A * 2 * B / mp.pi)      # semicircle of equal area
    sig, wW = westergaard(P, T, a_s, L, NU, E, K)
    print('\nIoannides et al. (1985) semicircle edge formulas, a_s = %s:' % mp.nstr(a_s, 8))
    print('  sigma_e = %s kPa  (M = %s)   delta_e = %s m' % (
        mp.nstr(sig, 8), mp.nstr(sig * T**2 / 6, 8), mp.nstr(wW, 8)))
    print('  exact Kirchhoff edge point-load coefficient w sqrt(E h^3 k)/P = %s ; sqrt(2+1.2nu) = %s'
          % (mp.nstr(edge_point_load_coefficient(), 8), mp.nstr(mp.sqrt(2 + mp.mpf('1.2') * NU), 8)))
    print('total time %.0f s' % (time.time() - t0))


if __name__ == '__main__':
    main()
