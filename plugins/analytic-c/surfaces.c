/* surfaces.c — planes and the surfaces of revolution: evaluation and inversion. */
#include "analytic.h"

const char *an_surface_kind_name(int kind) {
    switch (kind) {
    case AN_PLANE: return "plane";
    case AN_CYLINDER: return "cylinder";
    case AN_CONE: return "cone";
    case AN_SPHERE: return "sphere";
    case AN_TORUS: return "torus";
    default: return "?";
    }
}

int an_surface_periodic(const an_surface *s, int dir) {
    if (s->kind == AN_PLANE)
        return 0;
    return dir == 0 || s->kind == AN_TORUS;
}

double an_surface_scale(const an_surface *s, int dir, double model_size) {
    int angle = s->kind != AN_PLANE &&
                (dir == 0 || s->kind == AN_SPHERE || s->kind == AN_TORUS);
    return angle ? AN_TWO_PI : model_size;
}

/* The profile of a surface of revolution: rho (distance from the axis) and h (height along
   it) as functions of v, with their first and second derivatives. */
static void profile(const an_surface *s, double v, double rho[3], double h[3]) {
    double cv = cos(v), sv = sin(v);
    switch (s->kind) {
    case AN_CYLINDER:
        rho[0] = s->r, rho[1] = 0.0, rho[2] = 0.0;
        h[0] = v, h[1] = 1.0, h[2] = 0.0;
        break;
    case AN_CONE:
        rho[0] = s->r + v * s->sin_a, rho[1] = s->sin_a, rho[2] = 0.0;
        h[0] = v * s->cos_a, h[1] = s->cos_a, h[2] = 0.0;
        break;
    case AN_SPHERE:
        rho[0] = s->r * cv, rho[1] = -s->r * sv, rho[2] = -s->r * cv;
        h[0] = s->r * sv, h[1] = s->r * cv, h[2] = -s->r * sv;
        break;
    default: /* torus */
        rho[0] = s->big_r + s->r * cv, rho[1] = -s->r * sv, rho[2] = -s->r * cv;
        h[0] = s->r * sv, h[1] = s->r * cv, h[2] = -s->r * sv;
        break;
    }
}

void an_surface_eval(const an_surface *s, double u, double v, double out[18]) {
    int i;
    if (s->kind == AN_PLANE) {
        for (i = 0; i < 3; i++) {
            out[i] = s->c[i] + u * s->x[i] + v * s->y[i];
            out[3 + i] = s->x[i];
            out[6 + i] = s->y[i];
            out[9 + i] = out[12 + i] = out[15 + i] = 0.0;
        }
        return;
    }
    {
        double rho[3], h[3], cu = cos(u), su = sin(u);
        profile(s, v, rho, h);
        for (i = 0; i < 3; i++) {
            double e = cu * s->x[i] + su * s->y[i];  /* radial direction */
            double de = cu * s->y[i] - su * s->x[i]; /* its u derivative */
            out[i] = s->c[i] + rho[0] * e + h[0] * s->a[i];
            out[3 + i] = rho[0] * de;
            out[6 + i] = rho[1] * e + h[1] * s->a[i];
            out[9 + i] = -rho[0] * e;
            out[12 + i] = rho[1] * de;
            out[15 + i] = rho[2] * e + h[2] * s->a[i];
        }
    }
}

void an_surface_point(const an_surface *s, double u, double v, double out[3]) {
    int i;
    if (s->kind == AN_PLANE) {
        for (i = 0; i < 3; i++)
            out[i] = s->c[i] + u * s->x[i] + v * s->y[i];
        return;
    }
    {
        double rho[3], h[3], cu = cos(u), su = sin(u);
        profile(s, v, rho, h);
        for (i = 0; i < 3; i++)
            out[i] = s->c[i] + rho[0] * (cu * s->x[i] + su * s->y[i]) + h[0] * s->a[i];
    }
}

int an_surface_invert(const an_surface *s, const double p[3], double axis_tol, double uv[2]) {
    double d[3], px, py, pa, rho;
    an_sub(p, s->c, d);
    px = an_dot(d, s->x);
    py = an_dot(d, s->y);
    if (s->kind == AN_PLANE) {
        uv[0] = px;
        uv[1] = py;
        return 1;
    }
    pa = an_dot(d, s->a);
    rho = hypot(px, py);
    uv[0] = rho > axis_tol ? atan2(py, px) : 0.0;
    switch (s->kind) {
    case AN_CYLINDER:
        uv[1] = pa;
        break;
    case AN_CONE:
        /* the foot of p on the generator line through (r, 0) along (sin a, cos a) */
        uv[1] = (rho - s->r) * s->sin_a + pa * s->cos_a;
        break;
    case AN_SPHERE:
        uv[1] = atan2(pa, rho);
        break;
    default: /* torus */
        uv[1] = atan2(pa, rho - s->big_r);
        break;
    }
    return rho > axis_tol;
}
