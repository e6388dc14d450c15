//! `cube`: the unit cube; `cube_cavity`: the box [0,4]³ with a cube cavity [1.5,2.5]³.

use super::CaseWriter;
use glam::DVec3;

/// The unit cube [0,1]³: 8 vertices, 12 straight edges, 6 bilinear faces, one region.
pub fn cube() -> String {
    let mut w = CaseWriter::new(
        "cube",
        &[
            "The unit cube [0,1]^3: 8 vertices, 12 straight edges, 6 bilinear patches,",
            "one region. The smallest native solid; orientation is left to the loader.",
        ],
    );
    let (lo, hi) = (DVec3::ZERO, DVec3::ONE);
    w.mesh(lo.distance(hi) / 20.0, 1e-9);
    let faces = write_box(&mut w, "", lo, hi, &[]);
    w.region("solid", &faces, &[]);
    w.finish()
}

/// The box [0,4]³ with a cube cavity [1.5,2.5]³: two shells, one region.
pub fn cube_cavity() -> String {
    let mut w = CaseWriter::new(
        "cube_cavity",
        &[
            "The box [0,4]^3 with a cube cavity [1.5,2.5]^3: one region bounded by two",
            "shells (outer 'box_', cavity 'cavity_'), 16 vertices, 24 edges, 12 faces.",
            "Tests shell orientation: the cavity's normals must point into the cavity.",
        ],
    );
    let (lo, hi) = (DVec3::ZERO, DVec3::splat(4.0));
    w.mesh(lo.distance(hi) / 20.0, 1e-8);
    let mut faces = write_box(&mut w, "box_", lo, hi, &[]);
    faces.extend(write_box(
        &mut w,
        "cavity_",
        DVec3::splat(1.5),
        DVec3::splat(2.5),
        &[],
    ));
    w.region("fluid", &faces, &[]);
    w.finish()
}

/// An axis-aligned box `[lo, hi]`: 8 vertices, 12 straight edges and 6 bilinear faces, named
/// `<prefix>` + `xmin`/`xmax`/... for faces. `holes` adds inner loops to faces by side name
/// (e.g. `("ymin", [...])`). Returns the face names.
fn write_box(
    w: &mut CaseWriter,
    prefix: &str,
    lo: DVec3,
    hi: DVec3,
    holes: &[(&str, Vec<String>)],
) -> Vec<String> {
    const AXES: [&str; 3] = ["x", "y", "z"];
    let corner =
        |b: [usize; 3]| DVec3::new([lo.x, hi.x][b[0]], [lo.y, hi.y][b[1]], [lo.z, hi.z][b[2]]);
    let vname = |b: [usize; 3]| format!("{prefix}v{}{}{}", b[0], b[1], b[2]);
    // The edge along axis `a` through the corners with the other two bits of `b`.
    let ename = |a: usize, b: [usize; 3]| {
        let rest: String = (0..3)
            .filter(|&k| k != a)
            .map(|k| format!("{}{}", AXES[k], b[k]))
            .collect();
        format!("{prefix}{}_{rest}", AXES[a])
    };
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                w.vertex(&vname([i, j, k]), corner([i, j, k]));
            }
        }
    }
    for a in 0..3 {
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        for p in 0..2 {
            for q in 0..2 {
                let mut s = [0; 3];
                s[b] = p;
                s[c] = q;
                let mut e = s;
                e[a] = 1;
                w.edge(&ename(a, s), &vname(s), &vname(e), None);
            }
        }
    }
    let mut faces = Vec::new();
    for a in 0..3 {
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        for side in 0..2 {
            let name = format!("{prefix}{}{}", AXES[a], ["min", "max"][side]);
            let at = |p: usize, q: usize| {
                let mut s = [0; 3];
                s[a] = side;
                s[b] = p;
                s[c] = q;
                s
            };
            let surface = format!("{name}_plane");
            w.patch_surface(
                &surface,
                [
                    [corner(at(0, 0)), corner(at(0, 1))],
                    [corner(at(1, 0)), corner(at(1, 1))],
                ],
            );
            // Around the face: along b at q = 0, along c at p = 1, along b at q = 1, along c at p = 0.
            let outer = vec![
                ename(b, at(0, 0)),
                ename(c, at(1, 0)),
                ename(b, at(0, 1)),
                ename(c, at(0, 0)),
            ];
            let mut all = vec![outer];
            let side_name = format!("{}{}", AXES[a], ["min", "max"][side]);
            for (s, hole) in holes {
                if *s == side_name {
                    all.push(hole.clone());
                }
            }
            w.face(&name, &surface, &all);
            faces.push(name);
        }
    }
    faces
}
