"""BC + CH near in phase: the two stick-side segments summed as printed, against one integral
of their mirrored sum (proofs/certified-digits.md, "Near in phase: BC + CH as one integral").

    python3 benches/near_in_phase_identity.py

Needs mpmath. For v' = 1/P, P0 = 1, P1 = 0.4, Q1 = 0.2, f = 1 and φ from 0.4 down to 1e-8, it
prints the relative error of BC + CH computed at 15 and 30 digits, by the four-segment formulas
(BC and CH apart) and by the one integral over s ∈ [−δ, 0] of

    H(s) = −f Q1 P1 cos(α − s) sin(c − s) [v'(P(c − s)) − v'(P(c + s))]
           − Q1² sin 2α cos 2s · v'(P(c + s)),

c = θ_C (taken near 0), α = c − φ, each against the formulas at 60 digits.
"""

from mpmath import atan2, cos, fabs, mp, mpf, nstr, pi, quad, sin


def slope(load):
    return 1 / load


def apart(p0, p1, q1, phi, f):
    """BC and CH by the four-segment formulas, at the working precision."""
    theta_e = atan2(q1 * sin(phi), q1 * cos(phi) - f * p1)
    theta_a = atan2(q1 * sin(phi), q1 * cos(phi) + f * p1)
    delta = theta_e - theta_a
    theta_c = theta_e + pi
    theta_b, theta_h = theta_c - delta, theta_c + delta

    def normal(t):
        return p0 + p1 * cos(t)

    def tangential(t):
        return q1 * cos(t - phi)

    def normal_rate(t):
        return -p1 * sin(t)

    def tangential_rate(t):
        return -q1 * sin(t - phi)

    bc = quad(
        lambda t: tangential(t) * slope(normal(t)) * tangential_rate(t),
        [theta_b, theta_c],
    )
    ch = quad(
        lambda t: (
            tangential(t)
            * (
                f * slope(normal(t)) * normal_rate(t)
                - slope(normal(2 * theta_c - t))
                * (f * normal_rate(t) - tangential_rate(t))
            )
        ),
        [theta_c, theta_h],
    )
    return bc + ch


def mirrored(p0, p1, q1, phi, f):
    """BC + CH as one integral of the mirrored sum, at the working precision."""
    c = -atan2(q1 * sin(phi), f * p1 - q1 * cos(phi))
    delta = pi - atan2(2 * f * p1 * q1 * sin(phi), (f * p1) ** 2 - q1**2)
    alpha = c - phi

    def integrand(s):
        low, high = p0 + p1 * cos(c + s), p0 + p1 * cos(c - s)
        change = slope(high) - slope(low)
        stick = q1 * q1 * sin(2 * alpha) * cos(2 * s) * slope(low)
        return -f * q1 * p1 * cos(alpha - s) * sin(c - s) * change - stick

    return quad(integrand, [-delta, 0])


def main():
    cycle = ("1", "0.4", "0.2")
    for phi in ("0.4", "1e-3", "1e-8"):
        mp.dps = 60
        exact = apart(*map(mpf, cycle), mpf(phi), mpf(1))
        row = [f"phi = {phi:5}", f"BC + CH = {nstr(exact, 12)}"]
        for name, method in (("apart", apart), ("one integral", mirrored)):
            for digits in (15, 30):
                mp.dps = digits
                value = method(*map(mpf, cycle), mpf(phi), mpf(1))
                mp.dps = 60
                row.append(f"{name} at {digits}: {nstr(fabs(value / exact - 1), 2)}")
        print("   ".join(row))


if __name__ == "__main__":
    main()
