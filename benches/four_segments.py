"""The four segment integrals of W in the cycle angle (src/dissipation/segments.rs,
proofs/four-segment.md), for the Python scripts that integrate them with another
library's quadrature: W = lambda * sum of the integrals over the pieces returned.

`m` is the math module the integrands use (`math`, or `mpmath` at its precision) and `pi`
its pi; `slope` is v'(P).
"""


def segment_pieces(P0, P1, Q1, f, phi, slope, m, pi):
    """[(integrand, points)] for EB, BC, CH and HE: each integrand over its segment, with
    the segment's ends and the lowest-load points inside it, in increasing order."""
    phi = m.fmod(phi, pi)
    plus = m.hypot(Q1 * m.cos(phi) + f * P1, Q1 * m.sin(phi))
    minus = m.hypot(Q1 * m.cos(phi) - f * P1, Q1 * m.sin(phi))
    theta_e = m.atan2(Q1 * m.sin(phi), Q1 * m.cos(phi) - f * P1)
    stick = m.atan2(2 * Q1 * f * P1 * m.sin(phi), Q1 ** 2 - (f * P1) ** 2)
    theta_c = theta_e + pi
    theta_b, theta_h = theta_c - stick, theta_c + stick
    p_t = P0 - (plus + minus) / (2 * f)

    def P(t):
        return P0 + P1 * m.cos(t)

    def dP(t):
        return -P1 * m.sin(t)

    def Q(t):  # Q - Q0
        return Q1 * m.cos(t - phi)

    def eb(t):
        p_s = p_t + plus * m.sin((t - theta_b) / 2) ** 2 / f
        return Q(t) * (-f * slope(P(t)) * dP(t) + slope(p_s) * plus * m.sin(t - theta_b))

    def bc(t):
        return Q(t) * slope(P(t)) * -Q1 * m.sin(t - phi)

    def ch(t):
        return Q(t) * (f * slope(P(t)) * dP(t) - slope(P(2 * theta_c - t)) * minus * m.sin(t - theta_e))

    def he(t):
        p_k = p_t + minus * m.sin((t - theta_e) / 2) ** 2 / f
        return Q(t) * (f * slope(P(t)) * dP(t) - slope(p_k) * minus * m.sin(t - theta_e))

    def points(start, end, mirror=False):
        inside = []
        for k in range(-2, 4):
            lowest = (2 * k + 1) * pi
            for x in [lowest] + ([2 * theta_c - lowest] if mirror else []):
                if start < x < end:
                    inside.append(x)
        return [start] + sorted(inside) + [end]

    return [(eb, points(theta_e, theta_b)), (bc, points(theta_b, theta_c)),
            (ch, points(theta_c, theta_h, mirror=True)), (he, points(theta_h, theta_e + 2 * pi))]
