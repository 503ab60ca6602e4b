"""Independent reference values for the Ruina & Pratap ch. 10 seed cases.

Numpy-only, hand-style closed forms (no sympy.physics, nothing from mechgrade).
Every case function returns {objective_id: value} in the objective's unit from
/work/shared/cases/seed_examples.yaml: scalars as float, vectors as [x, y, z]
in the objective's frame/basis, symbolic objectives as expression strings.

Each closed form is cross-checked (assert) against a finite-difference
derivative of an explicit position-vs-time function built from the model in
ruina_models.md, so both the formula and the geometry reading are exercised.

Run:  python tests/data/independent/ruina.py
"""
import math

import numpy as np

Z = np.array([0.0, 0.0, 1.0])
D2R = math.pi / 180.0


def V(x, y, z=0.0):
    return np.array([x, y, z], dtype=float)


def wx(w, r):
    """(w k) x r for a scalar rate w about +z."""
    return w * np.cross(Z, r)


def rot(q):
    """Unit vectors (bx, by) of a frame turned by angle q (CCW, about +z) from N."""
    return V(math.cos(q), math.sin(q)), V(-math.sin(q), math.cos(q))


def fd(r, h=1e-4):
    """Central finite differences of a position function r(t) at t = 0: (v, a)."""
    return (r(h) - r(-h)) / (2 * h), (r(h) - 2 * r(0.0) + r(-h)) / h**2


def close(a, b, tol=1e-5):
    assert np.allclose(np.asarray(a, float), np.asarray(b, float), rtol=tol, atol=tol), (a, b)


def out(v):
    """Vector -> [x, y, z] list with round-off zeros cleaned."""
    return [0.0 if abs(c) < 1e-12 else float(c) for c in np.asarray(v, float)]


def path_quantities(v, a):
    """Path-coordinate recipe: speed, e_t, a_t, a_n, e_n, rho (rho = |v|^3/|v x a|)."""
    speed = np.linalg.norm(v)
    e_t = v / speed
    a_t = float(a @ e_t)
    an_vec = a - a_t * e_t
    a_n = np.linalg.norm(an_vec)
    rho = speed**3 / np.linalg.norm(np.cross(v, a))
    return speed, e_t, a_t, a_n, an_vec / a_n, rho


# ---------------------------------------------------------------- 10.1 ----
def ruina_10_1_cycloid():
    # Encoding with units: disk radius R = 1 m, hub speed Vh = 1 m/s, t in s.
    # Hub C = (Vh t, R); disk angle phi (CCW about +z) = -Vh t / R (rolls right);
    # rim point P = C + R (sin phi, -cos phi)  ->  x = t - sin t, y = 1 - cos t.
    R, Vh = 1.0, 1.0
    w = Vh / R                                   # |phidot|, disk turns clockwise

    def P(t):
        phi = -w * t
        return V(Vh * t, R) + R * V(math.sin(phi), -math.cos(phi))

    res = {}
    for tag, t0 in (("pi_2", math.pi / 2), ("pi", math.pi), ("2pi", 2 * math.pi)):
        v = V(Vh - R * w * math.cos(w * t0), R * w * math.sin(w * t0))      # dr/dt
        a = V(R * w**2 * math.sin(w * t0), R * w**2 * math.cos(w * t0))     # d2r/dt2
        vf, af = fd(lambda t, t0=t0: P(t0 + t))
        close(v, vf), close(a, af)
        res["v_" + tag] = out(v)
        res["speed_" + tag] = out([np.linalg.norm(v)])[0]
        if tag != "2pi":                            # cusp at 2 pi: e_t undefined
            _sp, e_t, *_, rho = path_quantities(v, a)
            res["e_t_" + tag] = out(e_t)
            res["rho_" + tag] = float(rho)
            close(rho, 4 * R * abs(math.sin(w * t0 / 2)))   # known cycloid result
    return res


# ---------------------------------------------------------------- 10.2 ----
def ruina_10_2_limacon():
    # R = (1 + 2 cos th) ft, th' = 3 rad/s const, at th = pi/2.
    th, thd, thdd = math.pi / 2, 3.0, 0.0
    R = 1 + 2 * math.cos(th)
    Rd = -2 * math.sin(th) * thd                              # chain rule
    Rdd = -2 * math.cos(th) * thd**2 - 2 * math.sin(th) * thdd
    v_pol = V(Rd, R * thd)                                    # (e_R, e_th)
    a_pol = V(Rdd - R * thd**2, 2 * Rd * thd + R * thdd)      # a_th = 2 R' th' + R th''
    eR, eth = rot(th)
    v = v_pol[0] * eR + v_pol[1] * eth
    a = a_pol[0] * eR + a_pol[1] * eth
    sp, e_t, a_t, a_n, e_n, rho = path_quantities(v, a)

    def P(t):
        q = th + thd * t + thdd * t**2 / 2
        return (1 + 2 * math.cos(q)) * rot(q)[0]
    vf, af = fd(P)
    close(v, vf), close(a, af)
    # geometric check: polar curvature (R^2 + 2R'^2 - R R'')/(R^2 + R'^2)^1.5
    Rp, Rpp = -2 * math.sin(th), -2 * math.cos(th)
    close(1 / rho, (R**2 + 2 * Rp**2 - R * Rpp) / (R**2 + Rp**2) ** 1.5)
    return {"v_polar": out(v_pol), "a_polar": out(a_pol), "v_N": out(v), "a_N": out(a),
            "speed": float(sp), "a_t": a_t, "a_n": float(a_n), "rho": float(rho),
            "e_t_N": out(e_t), "e_n_N": out(e_n)}


# ---------------------------------------------------------------- 10.3 ----
def ruina_10_3_spiral_bug():
    # R = R0 e^(a th) [mm], R' = 2 mm/s const (R'' = 0), at th = pi.
    a_, R0, Rd, th = 0.182, 5.0, 2.0, math.pi
    R = R0 * math.exp(a_ * th)
    thd = Rd / (a_ * R)                  # R' = a R th'
    thdd = -a_ * thd**2                  # R'' = a R (th'' + a th'^2) = 0
    a_pol = V(0.0 - R * thd**2, 2 * Rd * thd + R * thdd)
    eR, eth = rot(th)
    a = a_pol[0] * eR + a_pol[1] * eth

    def P(t):                            # R(t) = R + Rd t, th = ln(R/R0)/a
        Rt = R + Rd * t
        return Rt * rot(math.log(Rt / R0) / a_)[0]
    close(a, fd(P, 1e-3)[1], 1e-4)
    return {"a_N": out(a), "a_polar": out(a_pol), "thetadot": thd, "thetaddot": thdd}


# ----------------------------------------------------------- 10.4/10.7 ----
def ruina_10_4_10_7_rotating_tube_accel():
    # Arm frame B (about +z, aligned with N now), w = 5, wd = 3; P = 2L b_x + y b_y,
    # y = L, y' = -4 ft/s, y'' = -2 ft/s^2 (falls, speeding up).
    w, wd, L, yd, ydd = 5.0, 3.0, 2.0, -4.0, -2.0
    r = V(2 * L, L)
    v_rel, a_rel = V(0, yd), V(0, ydd)
    a_Pp = wx(wd, r) - w**2 * r                  # point of B under P
    a_cor = 2 * wx(w, v_rel)
    a = a_Pp + a_cor + a_rel

    def P(t, moving=True):
        q = w * t + wd * t**2 / 2
        bx, by = rot(q)
        y = L + (yd * t + ydd * t**2 / 2 if moving else 0.0)
        return 2 * L * bx + y * by
    close(a, fd(P)[1]), close(a_Pp, fd(lambda t: P(t, False))[1])
    return {"a_P_N": out(a), "a_Pprime_N": out(a_Pp), "a_coriolis_N": out(a_cor),
            "a_rel_N": out(a_rel)}


# ---------------------------------------------------------------- 10.5 ----
def ruina_10_5_rod_collar_disk():
    # O = disk centre (origin). Rod angle th from +x (CCW): B - A = L(cos th, sin th).
    # Disk angle phi (CCW) of OB from +y: B - O = R(-sin phi, cos phi). th = phi = 30 deg
    # (OB _|_ AB, rod tangent to disk). Track: y = -h, h = L sin30 - R cos30 = 0.567 m.
    L, R, vA = 2.0, 0.5, -2.0
    th = phi = 30 * D2R
    # loop constraints differentiated (x_A' given):
    #   x: xA' - L sin th th' + R cos phi phi' = 0 ;  y: L cos th th' + R sin phi phi' = 0
    M = np.array([[-L * math.sin(th), R * math.cos(phi)],
                  [L * math.cos(th), R * math.sin(phi)]])
    thd, phid = np.linalg.solve(M, [-vA, 0.0])
    eAB = V(math.cos(th), math.sin(th))
    rBO = R * V(-math.sin(phi), math.cos(phi))
    v_A = V(vA, 0)
    v_B = wx(phid, rBO)
    close(v_B, v_A + wx(thd, L * eAB))           # same B from the rod side
    v_G = v_A + wx(thd, L / 2 * eAB)

    A0 = rBO - L * eAB                           # (-1.982, -0.567)

    def B_of(t):                                  # B = circle(A,L) ∩ circle(O,R), near B0
        A = A0 + v_A * t
        d = np.linalg.norm(A)
        u = -A / d
        s = (L**2 - R**2 + d**2) / (2 * d)
        hgt = math.sqrt(L**2 - s**2)
        cands = [A + s * u + sg * hgt * np.cross(Z, u) for sg in (1, -1)]
        return min(cands, key=lambda c: np.linalg.norm(c - rBO))
    def angles(t):                                # (th, phi) recovered from B(t)
        dB, B = B_of(t) - (A0 + v_A * t), B_of(t)
        return V(math.atan2(dB[1], dB[0]), math.atan2(-B[0], B[1]))
    close(v_B, fd(B_of)[0])
    close([thd, phid], fd(angles)[0][:2])
    return {"omega_AB_z": float(thd), "omega_D_z": float(phid), "v_G_N": out(v_G),
            "v_B_N": out(v_B)}


# ---------------------------------------------------------------- 10.6 ----
def ruina_10_6_rotating_tube_velocity():
    w, L, yd = 5.0, 2.0, -4.0
    v = wx(w, V(2 * L, L)) + V(0, yd)            # v_P' + v_rel
    close(v, fd(lambda t: rot(w * t)[0] * 2 * L + rot(w * t)[1] * (L + yd * t))[0])
    return {"v_P_N": out(v), "speed": float(np.linalg.norm(v))}


# ---------------------------------------------------------------- 10.8 ----
def ruina_10_8_collar_in_disk_track():
    # Disk frame angle phi = w t (track = disk x axis, along +x now); P = rho e_track,
    # rho = 0.3 m. Rod: P - A = L(cos th, sin th), th = 45 deg, A fixed pivot.
    L, r, w, th = 1.0, 0.4, 2.0, 45 * D2R
    rho = 0.75 * r
    # P on track:  v_P = rho' e + rho w e_perp ;  P on rod: v_P = th' L (-sin th, cos th)
    thd = rho * w / (L * math.cos(th))           # j-component
    rhod = -thd * L * math.sin(th)               # i-component
    v_rel = V(rhod, 0)
    v_P = wx(thd, L * V(math.cos(th), math.sin(th)))
    close(v_P, v_rel + wx(w, V(rho, 0)))

    A = V(rho, 0) - L * V(math.cos(th), math.sin(th))

    def P(t):                                     # intersection of track line and circle(A, L)
        e = rot(w * t)[0]
        ea = e @ A
        return (ea + math.sqrt(ea**2 - A @ A + L**2)) * e
    close(v_P, fd(P)[0])
    return {"omega_AB_z": thd, "v_rel_N": out(v_rel), "v_P_N": out(v_P)}


# ---------------------------------------------------------------- 10.9 ----
def ruina_10_9_unit_vector_rates():
    # Frame D turns at omega about +z; Qdot = omega k x Q for every Q fixed in D.
    res = {"eR_dot_x": "0", "eR_dot_y": "omega", "etheta_dot_x": "-omega",
           "etheta_dot_y": "0", "iprime_dot_x": "0", "iprime_dot_y": "omega",
           "jprime_dot_x": "-omega", "jprime_dot_y": "0"}
    omega, q0, beta = 1.7, 0.4, 0.9               # arbitrary check values
    for name, off in (("eR", beta), ("iprime", 0.0)):
        e1 = lambda t, off=off: rot(q0 + omega * t + off)[0]
        e2 = lambda t, off=off: rot(q0 + omega * t + off)[1]
        ax, ay = (("eR", "etheta") if name == "eR" else ("iprime", "jprime"))
        for vec, nm in ((e1, ax), (e2, ay)):
            d = fd(vec)[0]
            close(d @ e1(0), eval(res[nm + "_dot_x"], {"omega": omega}))
            close(d @ e2(0), eval(res[nm + "_dot_y"], {"omega": omega}))
    return res


# --------------------------------------------------------------- 10.10 ----
def ruina_10_10_collar_bent_arm():
    # Arm frame (aligned with N now), w = 5 CCW; A = O + 1 m * lam, lam at -60 deg;
    # C = A + s b_x, s = 0.2 m, s' = 0.5 m/s.
    w, OA, s, sd = 5.0, 1.0, 0.2, 0.5
    lam = V(math.cos(-60 * D2R), math.sin(-60 * D2R))
    rC = OA * lam + V(s, 0)
    v = V(sd, 0) + wx(w, rC)                      # B(rdot) + w x r
    q = math.atan2(lam[1], lam[0])

    def C(t):
        bx, _ = rot(w * t)
        return OA * rot(q + w * t)[0] + (s + sd * t) * bx
    close(v, fd(C)[0])
    return {"v_C_N": out(v), "speed": float(np.linalg.norm(v))}


# --------------------------------------------------------------- 10.11 ----
def ruina_10_11_wheel_on_rotating_rod():
    # Rod angle q1 = 30 deg, q1' = 3, q1'' = 0. Wheel relative angle rate q2' = -5,
    # q2'' = -1 (clockwise, speeding up). P - A = r(cos30, -sin30).
    L, r, w1, w2, w2d = 2.0, 0.5, 3.0, -5.0, -1.0
    th = 30 * D2R
    rA = L * V(math.cos(th), math.sin(th))
    rPA = r * V(math.cos(th), -math.sin(th))
    rP = rA + rPA
    v_rel = wx(w2, rPA)
    v = wx(w1, rP) + v_rel
    a_Pp = -w1**2 * rP                            # w1 constant
    a_cor = 2 * wx(w1, v_rel)
    a_rel = wx(w2d, rPA) - w2**2 * rPA
    a = a_Pp + a_cor + a_rel
    # second route: absolute wheel rate w1 + w2, a_P = a_A + alpha x r - w^2 r
    close(a, -w1**2 * rA + wx(w2d, rPA) - (w1 + w2) ** 2 * rPA)

    def P(t):
        q1 = th + w1 * t
        psi = -th + (w1 + w2) * t + w2d * t**2 / 2     # absolute angle of A->P
        return L * rot(q1)[0] + r * rot(psi)[0]
    vf, af = fd(P)
    close(v, vf), close(a, af)
    return {"v_P_N": out(v), "a_P_N": out(a), "a_Pprime_N": out(a_Pp),
            "a_coriolis_N": out(a_cor), "a_rel_N": out(a_rel)}


# ---------------------------------------------------- Sec. 10 bug on tire --
def ruina_sec10_bug_on_tire():
    # Hub O' = (d, R) with d = R th; tire frame turned by -th (omega = -th' k);
    # P = O' + s b_x + l b_y (s const). v = R th' i + (l th') b_x + (l' - s th') b_y.
    res = {"v_hub_i": "R*thetad", "v_rest_iprime": "l*thetad",
           "v_rest_jprime": "ld - s*thetad", "a_hub_i": "R*thetadd",
           "a_rest_iprime": "l*thetadd - s*thetad**2 + 2*thetad*ld",
           "a_rest_jprime": "ldd - s*thetadd - l*thetad**2"}
    vals = dict(R=0.35, s=0.12, theta=0.7, thetad=2.3, thetadd=-1.1, l=0.08, ld=0.05,
                ldd=-0.3)
    g = lambda k: eval(res[k], {}, vals)

    def P(t):
        th = vals["theta"] + vals["thetad"] * t + vals["thetadd"] * t**2 / 2
        l = vals["l"] + vals["ld"] * t + vals["ldd"] * t**2 / 2
        bx, by = rot(-th)
        return V(vals["R"] * th, vals["R"]) + vals["s"] * bx + l * by
    vf, af = fd(P, 1e-3)
    bx, by = rot(-vals["theta"])
    close(vf, g("v_hub_i") * V(1, 0) + g("v_rest_iprime") * bx + g("v_rest_jprime") * by)
    close(af, g("a_hub_i") * V(1, 0) + g("a_rest_iprime") * bx + g("a_rest_jprime") * by, 1e-4)
    return res


CASES = [ruina_10_1_cycloid, ruina_10_2_limacon, ruina_10_3_spiral_bug,
         ruina_10_4_10_7_rotating_tube_accel, ruina_10_5_rod_collar_disk,
         ruina_10_6_rotating_tube_velocity, ruina_10_8_collar_in_disk_track,
         ruina_10_9_unit_vector_rates, ruina_10_10_collar_bent_arm,
         ruina_10_11_wheel_on_rotating_rod, ruina_sec10_bug_on_tire]


def _fmt(v):
    if isinstance(v, list):
        return "[" + ", ".join(f"{c:.6g}" for c in v) + "]"
    return f"{v:.6g}" if isinstance(v, float) else str(v)


if __name__ == "__main__":
    for f in CASES:
        print(f.__name__)
        for k, v in f().items():
            print(f"  {k:14s} {_fmt(v)}")
