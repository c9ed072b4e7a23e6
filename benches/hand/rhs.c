/* Hand-written C right-hand sides, the baseline of `codegen_c` (the
 * generated C measured against them): what a careful programmer writes
 * from the textbook formulas, parameters as arguments like the generated
 * code, sin and cos of one angle next to each other (GCC merges them into
 * one sincos), y = (q, q'), dy = (q', q''). */
#include <math.h>

/* theta'' = -g/l sin(theta) */
int hand_pendulum_rhs(double t, const double *y, double m, double l, double g, double *dy)
{
    (void)t;
    (void)m;
    dy[0] = y[1];
    dy[1] = -g / l * sin(y[0]);
    return 0;
}

/* The double pendulum with equal masses and lengths (angles from the
 * downward vertical), d = q1 - q2:
 * q1'' = (-3 g sin q1 - g sin(q1 - 2 q2) - 2 sin d (l q2'^2 + l q1'^2 cos d)) / (l (3 - cos 2d))
 * q2'' = 2 sin d (2 l q1'^2 + 2 g cos q1 + l q2'^2 cos d) / (l (3 - cos 2d)) */
int hand_double_pendulum_rhs(double t, const double *y, double m, double l, double g, double *dy)
{
    (void)t;
    (void)m;
    const double q1 = y[0], q2 = y[1], w1 = y[2], w2 = y[3];
    const double d = q1 - q2;
    const double sd = sin(d), cd = cos(d);
    const double s1 = sin(q1), c1 = cos(q1);
    const double c2d = cd * cd - sd * sd;
    const double den = l * (3.0 - c2d);
    const double a = l * w1 * w1, b = l * w2 * w2;
    dy[0] = w1;
    dy[1] = w2;
    dy[2] = (-3.0 * g * s1 - g * sin(q1 - 2.0 * q2) - 2.0 * sd * (b + a * cd)) / den;
    dy[3] = 2.0 * sd * (2.0 * a + 2.0 * g * c1 + b * cd) / den;
    return 0;
}

/* Seed 24.2: M = diag(4m, 3/2 m), f = (k (x2 - 2 x1), k (x1 - x2)). */
int hand_seed_24_2_rhs(double t, const double *y, double m, double k, double R, double *dy)
{
    (void)t;
    (void)R;
    const double x1 = y[0], x2 = y[1];
    const double a = k / m;
    dy[0] = y[2];
    dy[1] = y[3];
    dy[2] = a * (0.25 * x2 - 0.5 * x1);
    dy[3] = a * (x1 - x2) * (2.0 / 3.0);
    return 0;
}
