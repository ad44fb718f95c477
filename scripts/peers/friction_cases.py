"""The stiff friction cases of friction-lab written out for scipy: the belt rig
m·x'' + c·x' + k·x = −F(x' − v_belt) (docs/models.md, scenario `belt`, its defaults m = 1 kg,
k = 100 N/m, c = 0, v_belt = 0.05 m/s, x0 = v0 = 0, 20 s) with the paper's parameter set
(F_s = 7.5 N, F_c = 6 N, v_s = 0.1 m/s, C1 = C2 = 1.5 N, σ0 = 1e5 N/m, σ1 = √1e5 N·s/m,
σ2 = 0.4 N·s/m), under two laws that make it stiff:

- `belt-lugre`: LuGre (docs/models.md), F = σ0·z + σ1·ż + σ2·v_r,
  ż = v_r − σ0·|v_r|·z/g(v_r), g(v) = F_c + (F_s − F_c)·exp(−(v/v_s)²); state (x, v, z);
- `belt-regularized`: CS regularised at ε = 1e-4 m/s, sign(v) ≈ tanh(v/ε):
  F = F_c·tanh(v_r/ε) + exp(−(v_r/v_s)²)·(C1·(1 + tanh)/2 − C2·(1 − tanh)/2); state (x, v).

Each with its analytic Jacobian, and the `friction-lab simulate` options that run the same
case. The scripts that use them check the equations against friction-lab's: both codes at
rtol = atol = 1e-12 must agree at the end time.
"""

import math

M, K, C, V_BELT = 1.0, 100.0, 0.0, 0.05
F_S, F_C, V_S, C1, C2 = 7.5, 6.0, 0.1, 1.5, 1.5
SIGMA0, SIGMA1, SIGMA2 = 1e5, math.sqrt(1e5), 0.4
EPSILON = 1e-4
T_END = 20.0


def lugre(t, y):
    x, v, z = y
    vr = v - V_BELT
    g = F_C + (F_S - F_C) * math.exp(-((vr / V_S) ** 2))
    zdot = vr - SIGMA0 * abs(vr) * z / g
    force = SIGMA0 * z + SIGMA1 * zdot + SIGMA2 * vr
    return [v, (-K * x - C * v - force) / M, zdot]


def lugre_jac(t, y):
    x, v, z = y
    vr = v - V_BELT
    e = math.exp(-((vr / V_S) ** 2))
    g = F_C + (F_S - F_C) * e
    dg = (F_S - F_C) * e * (-2 * vr / V_S**2)
    sign = math.copysign(1.0, vr) if vr != 0 else 0.0
    dzdot_dz = -SIGMA0 * abs(vr) / g
    dzdot_dv = 1 - SIGMA0 * z * (sign * g - abs(vr) * dg) / g**2
    df_dz = SIGMA0 + SIGMA1 * dzdot_dz
    df_dv = SIGMA1 * dzdot_dv + SIGMA2
    return [
        [0.0, 1.0, 0.0],
        [-K / M, (-C - df_dv) / M, -df_dz / M],
        [0.0, dzdot_dv, dzdot_dz],
    ]


def regularized(t, y):
    x, v = y
    vr = v - V_BELT
    th = math.tanh(vr / EPSILON)
    e = math.exp(-((vr / V_S) ** 2))
    force = F_C * th + e * (C1 * (1 + th) / 2 - C2 * (1 - th) / 2)
    return [v, (-K * x - C * v - force) / M]


def regularized_jac(t, y):
    x, v = y
    vr = v - V_BELT
    th = math.tanh(vr / EPSILON)
    dth = (1 - th**2) / EPSILON
    e = math.exp(-((vr / V_S) ** 2))
    de = e * (-2 * vr / V_S**2)
    stribeck = C1 * (1 + th) / 2 - C2 * (1 - th) / 2
    df_dv = F_C * dth + de * stribeck + e * (C1 + C2) / 2 * dth
    return [[0.0, 1.0], [-K / M, (-C - df_dv) / M]]


# name: (f, jac, y0, t_end, the options of `friction-lab simulate` for the same case).
CASES = {
    "belt-lugre": (lugre, lugre_jac, [0.0, 0.0, 0.0], T_END,
                   ["belt", "--model", "lugre", "--set", "sigma0=1e5"]),
    "belt-regularized": (regularized, regularized_jac, [0.0, 0.0], T_END,
                         ["belt", "--model", "CS", "--switching", "regularized",
                          "--set", f"epsilon={EPSILON}"]),
}
