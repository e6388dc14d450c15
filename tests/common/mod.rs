//! Case-file text for tests: axis-aligned boxes made of bilinear patches.
#![allow(dead_code)]

pub mod corpus;
pub mod occt;
pub mod plate;
pub mod plugins;
pub mod readers;
pub mod server;
pub mod wake;

/// Vertices, edges, surfaces and faces of the box [lo, hi]³ with names prefixed by `p`.
/// `flip` lists loops in reverse order to show that users need not orient anything.
pub fn box_entities(p: &str, lo: f64, hi: f64, flip: bool) -> (String, Vec<String>) {
    cuboid_entities(p, [lo; 3], [hi; 3], flip)
}

/// [`box_entities`] of the box [lo₀, hi₀] × [lo₁, hi₁] × [lo₂, hi₂]; face `{p}f{axis}{side}`
/// lies at `lo[axis]` (side 0) or `hi[axis]` (side 1).
pub fn cuboid_entities(p: &str, lo: [f64; 3], hi: [f64; 3], flip: bool) -> (String, Vec<String>) {
    let at = |axis: usize, i: usize| if i == 0 { lo[axis] } else { hi[axis] };
    let mut s = String::new();
    for (x, y, z) in corners() {
        s += &format!(
            "[[vertex]]\nname = \"{p}v{x}{y}{z}\"\npoint = [{}, {}, {}]\n",
            at(0, x),
            at(1, y),
            at(2, z)
        );
    }
    let mut edges = Vec::new();
    for (a, b) in box_edges() {
        let name = format!("{p}e{}{}{}_{}{}{}", a.0, a.1, a.2, b.0, b.1, b.2);
        s += &format!(
            "[[edge]]\nname = \"{name}\"\nstart = \"{p}v{}{}{}\"\nend = \"{p}v{}{}{}\"\n",
            a.0, a.1, a.2, b.0, b.1, b.2
        );
        edges.push((a, b, name));
    }
    let mut faces = Vec::new();
    for axis in 0..3 {
        for side in 0..2 {
            let name = format!("{p}f{axis}{side}");
            // Corners of the face in (u,v) order: the other two axes.
            let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
            let corner = |i: usize, j: usize| {
                let mut k = [0; 3];
                k[axis] = side;
                k[a1] = i;
                k[a2] = j;
                (k[0], k[1], k[2])
            };
            let pt = |k: (usize, usize, usize)| {
                format!("[{}, {}, {}]", at(0, k.0), at(1, k.1), at(2, k.2))
            };
            s += &format!(
                "[[surface]]\nname = \"{name}\"\ncorners = [[{}, {}], [{}, {}]]\n",
                pt(corner(0, 0)),
                pt(corner(0, 1)),
                pt(corner(1, 0)),
                pt(corner(1, 1))
            );
            let ring = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
            let mut names: Vec<String> = (0..4)
                .map(|k| {
                    let (a, b) = (ring[k], ring[(k + 1) % 4]);
                    edges
                        .iter()
                        .find(|(x, y, _)| (*x == a && *y == b) || (*x == b && *y == a))
                        .map(|(_, _, n)| format!("\"{n}\""))
                        .unwrap()
                })
                .collect();
            if flip {
                names.reverse();
            }
            s += &format!(
                "[[face]]\nname = \"{name}\"\nsurface = \"{name}\"\nloops = [[{}]]\n",
                names.join(", ")
            );
            faces.push(name);
        }
    }
    (s, faces)
}

fn corners() -> Vec<(usize, usize, usize)> {
    let mut v = Vec::new();
    for x in 0..2 {
        for y in 0..2 {
            for z in 0..2 {
                v.push((x, y, z));
            }
        }
    }
    v
}

type Corner = (usize, usize, usize);

fn box_edges() -> Vec<(Corner, Corner)> {
    let mut e = Vec::new();
    for a in corners() {
        for b in corners() {
            let diff = (a.0 != b.0) as u8 + (a.1 != b.1) as u8 + (a.2 != b.2) as u8;
            if diff == 1 && a < b {
                e.push((a, b));
            }
        }
    }
    e
}

/// A one-region case of the box [0, 4]³ with the cube [1.5, 2.5]³ as a cavity.
pub fn box_with_cavity(size: f64) -> String {
    let (outer, of) = box_entities("o", 0.0, 4.0, false);
    let (inner, inf) = box_entities("i", 1.5, 2.5, true);
    let faces: Vec<String> = of.iter().chain(&inf).map(|f| format!("\"{f}\"")).collect();
    format!(
        "[mesh]\nsize = {size}\n{outer}{inner}[[region]]\nname = \"fluid\"\nfaces = [{}]\n",
        faces.join(", ")
    )
}

/// The box [0, 1]³ with two cavities facing each other across a gap `gap` wide at x = 0.5:
/// [0.5 − gap/2 − 0.25, 0.5 − gap/2] and [0.5 + gap/2, 0.5 + gap/2 + 0.25] in x, [0.3, 0.7]
/// in y and z; their faces are named `a…` and `b…`.
pub fn two_cavities_across_a_gap(size: f64, gap: f64) -> String {
    let (outer, of) = box_entities("o", 0.0, 1.0, false);
    let (x0, x1) = (0.5 - 0.5 * gap, 0.5 + 0.5 * gap);
    let (a, af) = cuboid_entities("a", [x0 - 0.25, 0.3, 0.3], [x0, 0.7, 0.7], true);
    let (b, bf) = cuboid_entities("b", [x1, 0.3, 0.3], [x1 + 0.25, 0.7, 0.7], true);
    let faces: Vec<String> = (of.iter().chain(&af).chain(&bf))
        .map(|f| format!("\"{f}\""))
        .collect();
    format!(
        "[mesh]\nsize = {size}\n{outer}{a}{b}[[region]]\nname = \"fluid\"\nfaces = [{}]\n",
        faces.join(", ")
    )
}

/// A one-region case of the unit cube.
pub fn unit_cube(size: f64) -> String {
    let (ents, f) = box_entities("", 0.0, 1.0, false);
    let faces: Vec<String> = f.iter().map(|f| format!("\"{f}\"")).collect();
    format!(
        "[mesh]\nsize = {size}\n{ents}[[region]]\nname = \"solid\"\nfaces = [{}]\n",
        faces.join(", ")
    )
}

/// The box [0, 4]³ with a square sheet (x, y in [1, 3], z = 2, a bilinear patch slightly
/// warped upwards at one corner) embedded in its region: a wake-like face with four free edges.
pub fn box_with_sheet(size: f64) -> String {
    let (ents, f) = box_entities("", 0.0, 4.0, false);
    let faces: Vec<String> = f.iter().map(|f| format!("\"{f}\"")).collect();
    let mut s = format!("[mesh]\nsize = {size}\n{ents}");
    let p = [
        [1.0, 1.0, 2.0],
        [3.0, 1.0, 2.0],
        [3.0, 3.0, 2.3],
        [1.0, 3.0, 2.0],
    ];
    for (k, q) in p.iter().enumerate() {
        s += &format!(
            "[[vertex]]\nname = \"s{k}\"\npoint = [{}, {}, {}]\n",
            q[0], q[1], q[2]
        );
    }
    for k in 0..4 {
        s += &format!(
            "[[edge]]\nname = \"se{k}\"\nstart = \"s{k}\"\nend = \"s{}\"\n",
            (k + 1) % 4
        );
    }
    let pt = |q: [f64; 3]| format!("[{}, {}, {}]", q[0], q[1], q[2]);
    s += &format!(
        "[[surface]]\nname = \"sheet\"\ncorners = [[{}, {}], [{}, {}]]\n",
        pt(p[0]),
        pt(p[3]),
        pt(p[1]),
        pt(p[2])
    );
    s += "[[face]]\nname = \"sheet\"\nsurface = \"sheet\"\nloops = [[\"se0\", \"se1\", \"se2\", \"se3\"]]\n";
    s += &format!(
        "[[region]]\nname = \"fluid\"\nfaces = [{}]\nembedded_faces = [\"sheet\"]\n",
        faces.join(", ")
    );
    s
}

/// Two unit cubes overlapping in [0.5, 1]³ but listed as one region's shell: a
/// self-intersecting boundary.
pub fn overlapping_boxes(size: f64) -> String {
    let (a, fa) = box_entities("a", 0.0, 1.0, false);
    let (b, fb) = box_entities("b", 0.5, 1.5, false);
    let faces: Vec<String> = fa.iter().chain(&fb).map(|f| format!("\"{f}\"")).collect();
    format!(
        "[mesh]\nsize = {size}\n{a}{b}[[region]]\nname = \"tangle\"\nfaces = [{}]\n",
        faces.join(", ")
    )
}

/// Two regions: the boxes [0,1]³ ("left") and [1,2]×[0,1]² ("right") sharing the face x = 1.
pub fn two_boxes(size: f64) -> String {
    let mut s = format!("[mesh]\nsize = {size}\n");
    let v = |i: usize, j: usize, k: usize| format!("v{i}{j}{k}");
    for i in 0..3 {
        for j in 0..2 {
            for k in 0..2 {
                s += &format!(
                    "[[vertex]]\nname = \"{}\"\npoint = [{i}, {j}, {k}]\n",
                    v(i, j, k)
                );
            }
        }
    }
    let mut edge = |a: (usize, usize, usize), b: (usize, usize, usize)| {
        let name = format!("{}_{}", v(a.0, a.1, a.2), v(b.0, b.1, b.2));
        s += &format!(
            "[[edge]]\nname = \"{name}\"\nstart = \"{}\"\nend = \"{}\"\n",
            v(a.0, a.1, a.2),
            v(b.0, b.1, b.2)
        );
        name
    };
    let mut edges = std::collections::HashMap::new();
    for i in 0..3 {
        for j in 0..2 {
            for k in 0..2 {
                let a = (i, j, k);
                for b in [(i + 1, j, k), (i, j + 1, k), (i, j, k + 1)] {
                    if b.0 < 3 && b.1 < 2 && b.2 < 2 {
                        edges.insert((a, b), edge(a, b));
                    }
                }
            }
        }
    }
    let e = |a: (usize, usize, usize), b: (usize, usize, usize)| {
        edges
            .get(&(a, b))
            .or_else(|| edges.get(&(b, a)))
            .unwrap()
            .clone()
    };
    let face = |s: &mut String, name: &str, c: [(usize, usize, usize); 4]| {
        let pt = |p: (usize, usize, usize)| format!("[{}, {}, {}]", p.0, p.1, p.2);
        *s += &format!(
            "[[surface]]\nname = \"{name}\"\ncorners = [[{}, {}], [{}, {}]]\n",
            pt(c[0]),
            pt(c[3]),
            pt(c[1]),
            pt(c[2])
        );
        let names: Vec<String> = (0..4)
            .map(|k| format!("\"{}\"", e(c[k], c[(k + 1) % 4])))
            .collect();
        *s += &format!(
            "[[face]]\nname = \"{name}\"\nsurface = \"{name}\"\nloops = [[{}]]\n",
            names.join(", ")
        );
    };
    for i in 0..3 {
        face(
            &mut s,
            &format!("x{i}"),
            [(i, 0, 0), (i, 1, 0), (i, 1, 1), (i, 0, 1)],
        );
    }
    for b in 0..2 {
        for j in 0..2 {
            face(
                &mut s,
                &format!("y{j}_{b}"),
                [(b, j, 0), (b + 1, j, 0), (b + 1, j, 1), (b, j, 1)],
            );
        }
        for k in 0..2 {
            face(
                &mut s,
                &format!("z{k}_{b}"),
                [(b, 0, k), (b + 1, 0, k), (b + 1, 1, k), (b, 1, k)],
            );
        }
    }
    for (b, name) in ["left", "right"].iter().enumerate() {
        s += &format!(
            "[[region]]\nname = \"{name}\"\nfaces = [\"x{b}\", \"x{}\", \"y0_{b}\", \"y1_{b}\", \"z0_{b}\", \"z1_{b}\"]\n",
            b + 1
        );
    }
    s
}

/// The box [0, 4]³ with an embedded edge (a free straight wire, on no face) from `a` to `b`.
pub fn box_with_wire(size: f64, a: [f64; 3], b: [f64; 3]) -> String {
    let (ents, f) = box_entities("", 0.0, 4.0, false);
    let faces: Vec<String> = f.iter().map(|f| format!("\"{f}\"")).collect();
    let mut s = format!("[mesh]\nsize = {size}\n{ents}");
    for (name, q) in [("w0", a), ("w1", b)] {
        s += &format!(
            "[[vertex]]\nname = \"{name}\"\npoint = [{}, {}, {}]\n",
            q[0], q[1], q[2]
        );
    }
    s += "[[edge]]\nname = \"wire\"\nstart = \"w0\"\nend = \"w1\"\n";
    s += &format!(
        "[[region]]\nname = \"fluid\"\nfaces = [{}]\nembedded_edges = [\"wire\"]\n",
        faces.join(", ")
    );
    s
}
