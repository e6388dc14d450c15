/* curves.c — lines and circles: evaluation and closest points, all in closed form. */
#include "analytic.h"

const char *an_curve_kind_name(int kind) {
    return kind == AN_LINE ? "line" : kind == AN_CIRCLE ? "circle" : "?";
}

void an_curve_eval(const an_curve *c, double t, double out[9]) {
    int i;
    if (c->kind == AN_LINE) {
        for (i = 0; i < 3; i++) {
            out[i] = c->c[i] + t * c->a[i];
            out[3 + i] = c->a[i];
            out[6 + i] = 0.0;
        }
        return;
    }
    {
        double ct = cos(t), st = sin(t);
        for (i = 0; i < 3; i++) {
            double radial = ct * c->x[i] + st * c->y[i];
            out[i] = c->c[i] + c->r * radial;
            out[3 + i] = c->r * (ct * c->y[i] - st * c->x[i]);
            out[6 + i] = -c->r * radial;
        }
    }
}

void an_curve_point(const an_curve *c, double t, double out[3]) {
    double d[9];
    an_curve_eval(c, t, d);
    out[0] = d[0];
    out[1] = d[1];
    out[2] = d[2];
}

static double clamp(double t, double lo, double hi) {
    return t < lo ? lo : t > hi ? hi : t;
}

/* The end of the arc [t0, t1] nearer to p: where the closest angle falls outside the arc. */
static double nearer_end(const an_curve *c, const double p[3], double t0, double t1) {
    double a[3], b[3];
    an_curve_point(c, t0, a);
    an_curve_point(c, t1, b);
    return an_dist(a, p) <= an_dist(b, p) ? t0 : t1;
}

double an_curve_closest(const an_curve *c, const double p[3], const double *hint, double t0,
                        double t1) {
    double d[3], px, py, theta, t;
    int has_hint = hint && isfinite(*hint);
    an_sub(p, c->c, d);
    if (c->kind == AN_LINE)
        return clamp(an_dot(d, c->a), t0, t1);

    px = an_dot(d, c->x);
    py = an_dot(d, c->y);
    /* on the axis every point of the circle is as close: keep the hint */
    if (hypot(px, py) <= 1e-14 * (c->r + an_norm(d)))
        return has_hint ? clamp(*hint, t0, t1) : t0;
    theta = atan2(py, px);
    if (has_hint) {
        t = an_wrap_near(theta, *hint);
        if (t >= t0 && t <= t1)
            return t;
    }
    /* the first turn at or after t0 */
    t = theta + AN_TWO_PI * ceil((t0 - theta) / AN_TWO_PI);
    if (t < t0) /* only by rounding */
        t = t0;
    if (t <= t1)
        return t;
    return nearer_end(c, p, t0, t1);
}
