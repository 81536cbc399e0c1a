/*
 * Triangle transformations (paper section 2.1). For triangle (A, B, C) with unit normal N, the
 * matrix M = [A-C | B-C | N] (columns) with translation C maps the unit triangle (1,0,0),
 * (0,1,0), (0,0,0) onto the triangle and (0,0,1) onto N; the device stores M^-1 and C (columns
 * 0..2 and 3 of the result: T p = M^-1 (p - C), with p - C taken from the rebased ray origin in
 * the intersection unit, docs/numerics.md). After transforming a ray with T, the intersection
 * unit needs only t = -O'z / D'z, u = O'x + t D'x, v = O'y + t D'y, and D'z is the cosine with
 * the normal. Computed in double precision; the caller rounds M^-1 to fp24 and C to two fp24
 * words (exact for binary32 vertices).
 *
 * Degeneracy criterion (documented in docs/memory-image.md): the triangle is dropped if twice
 * its area is zero or not finite, or if the shape condition number ||S||_inf ||S^-1||_inf of
 * S = [A-C | B-C | N L] (L the longer of the two edges, so that size does not count, only shape:
 * about 1 for a well-shaped triangle, about the aspect ratio for a sliver) exceeds max_condition
 * (default 2^24: beyond it, rounding T to fp24 leaves no correct bit in u, v).
 */
#include <math.h>

#include "memimage.h"

static double row_norm_inf(const double m[3][3])
{
    double n = 0;
    for (int i = 0; i < 3; i++)
        n = fmax(n, fabs(m[i][0]) + fabs(m[i][1]) + fabs(m[i][2]));
    return n;
}

int mi_triangle_transform(const double a[3], const double b[3], const double c[3], double max_condition,
                          affine *t)
{
    double e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = a[k] - c[k];
        e2[k] = b[k] - c[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double twice_area = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(twice_area > 0) || !isfinite(twice_area))
        return 0;
    for (int k = 0; k < 3; k++)
        n[k] /= twice_area;

    const double len = fmax(sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]),
                            sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]));
    affine m, shape, inv, shape_inv;
    for (int i = 0; i < 3; i++) {
        m.m[i][0] = shape.m[i][0] = e1[i];
        m.m[i][1] = shape.m[i][1] = e2[i];
        m.m[i][2] = n[i];
        shape.m[i][2] = n[i] * len;
        m.m[i][3] = c[i];
        shape.m[i][3] = 0;
    }
    if (!affine_invert(&m, &inv) || !affine_invert(&shape, &shape_inv))
        return 0;
    double s3[3][3], si3[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            if (!isfinite(inv.m[i][j]))
                return 0;
            if (j < 3) {
                s3[i][j] = shape.m[i][j];
                si3[i][j] = shape_inv.m[i][j];
            }
        }
    if (!(row_norm_inf(s3) * row_norm_inf(si3) <= max_condition))
        return 0;
    *t = inv;
    for (int i = 0; i < 3; i++)
        t->m[i][3] = c[i];
    return 1;
}
