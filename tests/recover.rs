//! Flips on the Delaunay kernel and boundary recovery (small sizes: debug mode).

use std::collections::{BTreeSet, HashMap};

use tetrafoil::mesh::{validity, VolumeMesh};
use tetrafoil::volume::delaunay::{triangulate, Delaunay, FlipError, INF};
use tetrafoil::volume::recover::{recover_boundary, recover_boundary_and_segments, RecoveryReport};

struct Rng(u64);
impl Rng {
    fn f(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: usize) -> usize {
        (self.f() * n as f64) as usize % n
    }
}

fn random(n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut r = Rng(seed * 2 + 0x1234_5678_9abc);
    (0..n).map(|_| [r.f(), r.f(), r.f()]).collect()
}

fn quality(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3], d: &[f64; 3]) -> f64 {
    let s = |p: &[f64; 3], q: &[f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    let (u, v, w) = (s(a, d), s(b, d), s(c, d));
    let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]);
    let l2 = |x: [f64; 3]| x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    det / (l2(u) + l2(v) + l2(w) + l2(s(a, b)) + l2(s(b, c)) + l2(s(c, a))).powf(1.5)
}

fn tet_set(d: &Delaunay) -> BTreeSet<[u32; 4]> {
    d.tets()
        .map(|mut t| {
            t.sort_unstable();
            t
        })
        .collect()
}

fn volume(d: &Delaunay) -> f64 {
    d.tets()
        .map(|t| {
            let p = t.map(|v| d.point(v));
            quality_free_volume(&p)
        })
        .sum()
}

fn quality_free_volume(p: &[[f64; 3]; 4]) -> f64 {
    let s = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let (u, v, w) = (s(p[0], p[3]), s(p[1], p[3]), s(p[2], p[3]));
    (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]))
        / 6.0
}

// ---------------------------------------------------------------- flips

#[test]
fn random_flips_keep_the_triangulation_valid() {
    let pts = random(300, 1);
    let mut d = triangulate(&pts).unwrap();
    let v0 = volume(&d);
    let mut r = Rng(99);
    let (mut f23, mut rem) = (0, 0);
    for round in 0..600 {
        let ids: Vec<u32> = d.tet_ids().collect();
        let t = ids[r.below(ids.len())];
        if round % 2 == 0 {
            if d.flip23(t, r.below(4) as u8).is_ok() {
                f23 += 1;
            }
        } else {
            let v = d.tet(t);
            let (i, j) = (r.below(4), r.below(3));
            let j = if j >= i { j + 1 } else { j };
            if d.remove_edge(v[i], v[j], quality).is_ok() {
                rem += 1;
            }
        }
        if round % 50 == 0 {
            d.check_valid().unwrap();
        }
    }
    d.check_valid().unwrap();
    assert!(f23 > 50 && rem > 20, "2-3 flips {f23}, edge removals {rem}");
    assert!((volume(&d) - v0).abs() < 1e-12 * v0.abs().max(1.0));
    // The kernel still inserts into the flipped (non-Delaunay) triangulation.
    let more = random(200, 2);
    let out = d.insert_batch(&more).unwrap();
    assert!(out.duplicates.is_empty());
    d.check_valid().unwrap();
    assert_eq!(d.num_vertices(), 500);
}

#[test]
fn flip23_then_flip32_restores_the_tets() {
    let pts = random(100, 3);
    let mut d = triangulate(&pts).unwrap();
    let before = tet_set(&d);
    let mut done = 0;
    let ids: Vec<u32> = d.tet_ids().collect();
    for t in ids {
        if !d.is_live(t) {
            continue;
        }
        for f in 0..4u8 {
            let (u, g) = d.neighbor(t, f);
            if d.is_ghost(u) {
                continue;
            }
            let (a, b) = (d.tet(t)[f as usize], d.tet(u)[g as usize]);
            let Ok(new) = d.flip23(t, f) else { continue };
            assert!(new
                .iter()
                .all(|&x| d.tet(x).contains(&a) && d.tet(x).contains(&b)));
            d.check_valid().unwrap();
            let (_, ring) = d.tets_around_edge(a, b).unwrap();
            assert_eq!(ring.len(), 3);
            d.flip32(a, b).unwrap();
            assert!(!d.has_edge(a, b));
            assert_eq!(tet_set(&d), before);
            d.check().unwrap(); // Delaunay again
            done += 1;
            break;
        }
        if done >= 20 {
            break;
        }
    }
    assert_eq!(done, 20);
}

#[test]
fn flip_refusals() {
    let pts = random(60, 4);
    let mut d = triangulate(&pts).unwrap();
    let t = d.tet_ids().next().unwrap();
    // Constrained face: no 2-3 flip through it.
    let f = (0..4u8).find(|&f| !d.is_ghost(d.neighbor(t, f).0)).unwrap();
    d.set_constrained(t, f, true).unwrap();
    assert_eq!(d.flip23(t, f), Err(FlipError::Constrained));
    let fv = d.face_vertices(t, f);
    assert_eq!(
        d.remove_edge(fv[0], fv[1], quality),
        Err(FlipError::Constrained)
    );
    // A 3-2 flip needs exactly three tets around the edge.
    let v = d.tet(t);
    let (_, ring) = d.tets_around_edge(v[0], v[1]).unwrap();
    if ring.len() != 3 {
        assert!(matches!(d.flip32(v[0], v[1]), Err(FlipError::Degree(_))));
    }
    d.check_valid().unwrap();
}

/// A flat pentagonal bipyramid: the apex edge has five tets; removing it gives the 6 tets
/// over a triangulation of the pentagon.
#[test]
fn remove_edge_pentagonal_bipyramid() {
    let mut p = vec![[0.0, 0.0, 0.3], [0.0, 0.0, -0.3]];
    for k in 0..5 {
        let a = std::f64::consts::TAU * k as f64 / 5.0;
        p.push([a.cos(), a.sin(), 0.0]);
    }
    let mut d = triangulate(&p).unwrap();
    let (tets, ring) = d.tets_around_edge(0, 1).unwrap();
    assert_eq!(tets.len(), 5);
    assert_eq!(d.num_tets(), 5);
    assert!(!ring.contains(&INF));
    let v0 = volume(&d);
    let created = d.remove_edge(0, 1, quality).unwrap();
    assert_eq!(created.len(), 6);
    assert_eq!(d.num_tets(), 6);
    assert!(!d.has_edge(0, 1));
    d.check_valid().unwrap();
    assert!((volume(&d) - v0).abs() < 1e-14);
    // Every new tet has one apex and a pentagon triangle.
    for t in created {
        let v = d.tet(t);
        assert_eq!(v.iter().filter(|&&x| x < 2).count(), 1);
    }
    // Keeping a given triangle of the ring.
    let mut d = triangulate(&p).unwrap();
    use tetrafoil::volume::delaunay::Keep;
    d.remove_edge_with(0, 1, Keep::Triangle(2, 4, 5), quality)
        .unwrap();
    assert!(d.find_face_near(2, 4, 5).is_some());
    d.check_valid().unwrap();
}

// ---------------------------------------------------------------- surfaces

/// Points deduplicated by their bits.
#[derive(Default)]
struct Pts {
    p: Vec<[f64; 3]>,
    map: HashMap<[u64; 3], u32>,
}

impl Pts {
    fn id(&mut self, q: [f64; 3]) -> u32 {
        let k = q.map(f64::to_bits);
        if let Some(&i) = self.map.get(&k) {
            return i;
        }
        self.p.push(q);
        self.map.insert(k, self.p.len() as u32 - 1);
        self.p.len() as u32 - 1
    }
}

/// The surface of the box `lo..hi` with `n[k]` intervals along axis k, quads split along
/// alternating diagonals, outward oriented. `skip_x_lo` leaves out the face x = lo.
fn box_surface(
    pts: &mut Pts,
    lo: [f64; 3],
    hi: [f64; 3],
    n: [usize; 3],
    skip_x_lo: bool,
) -> Vec<[u32; 3]> {
    let coord = |k: usize, i: usize| lo[k] + (hi[k] - lo[k]) * i as f64 / n[k] as f64;
    let mut tris = Vec::new();
    for k in 0..3 {
        let (u, v) = ((k + 1) % 3, (k + 2) % 3); // u × v = +e_k
        for side in 0..2 {
            if k == 0 && side == 0 && skip_x_lo {
                continue;
            }
            let at = |i: usize, j: usize| {
                let mut q = [0.0; 3];
                q[k] = if side == 0 { lo[k] } else { hi[k] };
                q[u] = coord(u, i);
                q[v] = coord(v, j);
                q
            };
            for i in 0..n[u] {
                for j in 0..n[v] {
                    let c = [
                        pts.id(at(i, j)),
                        pts.id(at(i + 1, j)),
                        pts.id(at(i + 1, j + 1)),
                        pts.id(at(i, j + 1)),
                    ];
                    let mut t = if (i + j) % 2 == 0 {
                        [[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
                    } else {
                        [[c[0], c[1], c[3]], [c[1], c[2], c[3]]]
                    };
                    if side == 0 {
                        for x in &mut t {
                            x.swap(1, 2);
                        }
                    }
                    tris.extend(t);
                }
            }
        }
    }
    tris
}

fn area(d: &Delaunay, t: [u32; 3]) -> f64 {
    let [a, b, c] = t.map(|v| d.point(v));
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let x = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    0.5 * (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
}

/// Run recovery and check everything the contract says; returns the report and the number
/// of surface edges missing from the initial tetrahedralisation.
fn recover_and_check(pts: &[[f64; 3]], tris: &[[u32; 3]], name: &str) -> (RecoveryReport, usize) {
    let mut d = triangulate(pts).unwrap();
    let mut edges = BTreeSet::new();
    for t in tris {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            edges.insert((a.min(b), a.max(b)));
        }
    }
    let missing = edges.iter().filter(|&&(a, b)| !d.has_edge(a, b)).count();
    let missing_faces = tris
        .iter()
        .filter(|t| d.find_face_near(t[0], t[1], t[2]).is_none())
        .count();
    let area0: Vec<f64> = tris.iter().map(|&t| area(&d, t)).collect();
    let mut out = tris.to_vec();
    let mut parent: Vec<u32> = (0..tris.len() as u32).collect();
    let start = std::time::Instant::now();
    let rep = recover_boundary(&mut d, &mut out, &mut parent).unwrap();
    eprintln!(
        "{name}: {} triangles, {} edges ({missing} missing), {missing_faces} faces missing \
         → {rep:?}, {} triangles after, {:.3} s",
        tris.len(),
        edges.len(),
        out.len(),
        start.elapsed().as_secs_f64()
    );
    let r = d.check_valid().unwrap();
    assert_eq!(parent.len(), out.len());
    assert!(out.len() >= tris.len());
    // Suppression: what is not left on the surface was deleted or moved into the volume.
    let added = rep.steiner_on_edges + rep.steiner_on_faces;
    assert!(rep.steiner_removed <= added && rep.steiner_interior <= rep.steiner_removed);
    assert_eq!(rep.steiner_left_on_surface, added - rep.steiner_removed);
    assert_eq!(
        r.vertices,
        pts.len() + rep.steiner_interior + rep.steiner_left_on_surface,
        "{name}: vertices in the tets"
    );
    if rep.steiner_left_on_surface == 0 {
        // Every Steiner point suppressed: the input surface, exactly, in input order.
        assert_eq!(out, tris, "{name}: surface not restored");
        assert!(parent.iter().enumerate().all(|(k, &p)| p == k as u32));
    }
    for (k, &t) in out.iter().enumerate() {
        let (tet, f) = d
            .find_face_near(t[0], t[1], t[2])
            .unwrap_or_else(|| panic!("{name}: triangle {k} {t:?} missing"));
        assert!(
            d.is_constrained(tet, f),
            "{name}: triangle {k} not constrained"
        );
    }
    assert!(r.constrained_faces >= out.len());
    let mut sum = vec![0.0; tris.len()];
    for (k, &t) in out.iter().enumerate() {
        sum[parent[k] as usize] += area(&d, t);
    }
    for (k, (&s, &a0)) in sum.iter().zip(&area0).enumerate() {
        assert!(
            (s - a0).abs() <= 1e-12 * a0,
            "{name}: triangle {k} area {s} vs {a0}"
        );
    }
    // Orientation kept: each piece's normal agrees with its parent's.
    for (k, &t) in out.iter().enumerate() {
        let n = |t: [u32; 3]| {
            let [a, b, c] = t.map(|v| d.point(v));
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ]
        };
        let (x, y) = (n(t), n(tris[parent[k] as usize]));
        assert!(
            x[0] * y[0] + x[1] * y[1] + x[2] * y[2] > 0.0,
            "{name}: piece {k} flipped"
        );
    }
    // Later insertions keep working on the recovered, constrained triangulation.
    let mut lo = [f64::MAX; 3];
    let mut hi = [f64::MIN; 3];
    for p in pts {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let extra: Vec<[f64; 3]> = random(50, 77)
        .into_iter()
        .map(|q| [0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) * (0.05 + 0.9 * q[k])))
        .collect();
    d.insert_batch(&extra).unwrap();
    d.check_valid().unwrap();
    for &t in &out {
        assert!(
            d.find_face_near(t[0], t[1], t[2]).is_some(),
            "{name}: lost after insertion"
        );
    }
    (rep, missing)
}

#[test]
fn cube_structured_cospherical() {
    let mut pts = Pts::default();
    let tris = box_surface(&mut pts, [0.0; 3], [1.0; 3], [6, 6, 6], false);
    assert_eq!(tris.len(), 6 * 36 * 2);
    let (rep, missing) = recover_and_check(&pts.p, &tris, "cube 6x6");
    assert!(
        missing > 0,
        "the lattice's Delaunay choice should miss some diagonals"
    );
    assert!(rep.flips >= missing);
    // Lattice degeneracies (coplanar rings) defeat a few hull flips: at most 3 Steiner points.
    assert!(rep.steiner_on_edges + rep.steiner_on_faces <= 3, "{rep:?}");
}

#[test]
fn cube_with_interior_and_exterior_points() {
    let mut pts = Pts::default();
    let tris = box_surface(&mut pts, [0.0; 3], [1.0; 3], [5, 5, 5], false);
    let mut p = pts.p.clone();
    p.extend(
        random(400, 5)
            .into_iter()
            .map(|q| q.map(|x| -0.5 + 2.0 * x)),
    );
    let (rep, _) = recover_and_check(&p, &tris, "cube + cloud");
    assert!(rep.flips > 0);
}

/// Schönhardt's twisted prism (radius 1, height 1, top turned by `twist` radians, sides split
/// along their reflex diagonals), outward oriented: no tetrahedralisation of its inside
/// without an extra point.
fn schoenhardt(twist: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut p = Vec::new();
    for z in [0.0, 1.0] {
        for k in 0..3 {
            let a = std::f64::consts::TAU * k as f64 / 3.0 + if z > 0.0 { twist } else { 0.0 };
            p.push([a.cos(), a.sin(), z]);
        }
    }
    // Quad (i, j, j+3, i+3): use the diagonal that is not on the convex hull (reflex).
    let o = |a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]| quality_free_volume(&[a, b, c, d]);
    let centre = [0.0, 0.0, 0.5];
    let mut tris = vec![[0, 2, 1], [3, 4, 5]];
    for i in 0..3u32 {
        let j = (i + 1) % 3;
        let q = |v: u32| p[v as usize];
        // Diagonal (i, j+3) is convex iff i+3 and the centre are on the same side of the
        // plane (i, j, j+3).
        let convex =
            (o(q(i), q(j), q(j + 3), q(i + 3)) > 0.0) == (o(q(i), q(j), q(j + 3), centre) > 0.0);
        if convex {
            tris.push([i, j, i + 3]);
            tris.push([j, j + 3, i + 3]);
        } else {
            tris.push([i, j, j + 3]);
            tris.push([i, j + 3, i + 3]);
        }
    }
    (p, tris)
}

/// Schönhardt's twisted prism: no tetrahedralisation without Steiner points. The ones on its
/// surface are suppressed afterwards; one must stay, inside the prism.
#[test]
fn schoenhardt_prism_needs_steiner_points() {
    let (p, tris) = schoenhardt(0.5);
    let (rep, missing) = recover_and_check(&p, &tris, "Schönhardt");
    assert!(missing >= 1);
    assert!(rep.steiner_on_edges + rep.steiner_on_faces >= 1, "{rep:?}");
    assert_eq!(rep.steiner_left_on_surface, 0, "{rep:?}");
    assert!(rep.steiner_interior >= 1, "{rep:?}");
}

/// The whole tetrahedralisation as a [`VolumeMesh`] (one region; `boundary` the recovered
/// triangles plus the hull's faces), for `mesh::validity`.
fn as_volume_mesh(d: &Delaunay, surface: &[[u32; 3]]) -> VolumeMesh {
    let mut m = VolumeMesh::default();
    let mut node = vec![u32::MAX; d.num_points()];
    let mut id = |m: &mut VolumeMesh, v: u32| {
        if node[v as usize] == u32::MAX {
            node[v as usize] = m.points.len() as u32;
            m.points.push(glam::DVec3::from_array(d.point(v)));
        }
        node[v as usize]
    };
    for t in d.tets() {
        let n = t.map(|v| id(&mut m, v));
        // Kernel tets have (a, b, c) facing away from d; the mesh wants it facing d.
        m.tets.push([n[0], n[2], n[1], n[3]]);
        m.tet_region.push(0);
    }
    for g in d.ghost_ids() {
        let t = d.tet(g);
        let i = t.iter().position(|&v| v == INF).unwrap();
        // The hull face as seen from the finite tet behind it faces out of that tet.
        let (u, f) = d.neighbor(g, i as u8);
        let b = d.face_vertices(u, f).map(|v| id(&mut m, v));
        m.boundary.push(b);
    }
    for t in surface {
        let b = t.map(|v| id(&mut m, v));
        m.boundary.push(b);
    }
    m.boundary_marker = vec![0; m.boundary.len()];
    m
}

/// The Schönhardt prism inside a box, points around it but none inside: the Steiner points
/// recovery puts on the prism are suppressed, the prism and box surfaces come back exactly
/// as input, one point ends up inside the prism, and the mesh passes `mesh::validity`.
#[test]
fn schoenhardt_prism_in_a_box_gets_its_surface_back() {
    let (prism, prism_tris) = schoenhardt(0.6);
    let mut pts = Pts::default();
    let mut tris = box_surface(&mut pts, [-3.0; 3], [3.0; 3], [3, 3, 3], false);
    let off = pts.p.len() as u32;
    let mut p = pts.p.clone();
    p.extend(&prism);
    tris.extend(prism_tris.iter().map(|t| t.map(|v| v + off)));
    let mut r = Rng(21);
    while p.len() < 200 {
        let q = [0, 1, 2].map(|_| -2.7 + 5.4 * r.f());
        let rr = (q[0] * q[0] + q[1] * q[1]).sqrt();
        if rr > 1.4 || q[2] < -0.4 || q[2] > 1.4 {
            p.push(q);
        }
    }
    let (rep, _) = recover_and_check(&p, &tris, "Schönhardt in a box");
    assert!(rep.steiner_on_edges + rep.steiner_on_faces >= 1, "{rep:?}");
    assert_eq!(rep.steiner_left_on_surface, 0, "{rep:?}");
    assert!(rep.steiner_interior >= 1, "{rep:?}");

    // Again, to look at the mesh itself (recover_and_check inserts more points after).
    let mut d = triangulate(&p).unwrap();
    let mut out = tris.clone();
    let mut parent = Vec::new();
    let rep2 = recover_boundary(&mut d, &mut out, &mut parent).unwrap();
    assert_eq!(rep2, rep);
    assert_eq!(out, tris);
    let mesh = as_volume_mesh(&d, &out);
    let v = validity::check(&mesh);
    assert!(v.is_valid(), "{:?}", v.defects);
    assert!((v.volume - 216.0).abs() < 1e-9, "{}", v.volume);
    // The point left inside is strictly inside the prism: every prism triangle sees it on
    // the side of the axis point (0, 0, 0.5), which is inside.
    let inside: Vec<u32> = (p.len() as u32..d.num_points() as u32)
        .filter(|&m| d.vertex_tet(m).is_some())
        .collect();
    assert_eq!(inside.len(), rep.steiner_interior);
    for &m in &inside {
        let pm = d.point(m);
        for t in &prism_tris {
            let [a, b, c] = t.map(|v| prism[v as usize]);
            let centre = quality_free_volume(&[a, b, c, [0.0, 0.0, 0.5]]);
            assert!(
                quality_free_volume(&[a, b, c, pm]) * centre > 0.0,
                "{pm:?} outside"
            );
        }
    }
}

/// A thin 100 × 100 × 1 box (3.3-unit triangles, 30 × 30 per big face, 30 × 1 per side)
/// inside a cloud of points: long edges and faces are cut by many tets, so flips alone
/// cannot recover them. (With needle faces, 33 × 1, Steiner points cascade: see report.)
#[test]
fn thin_box_in_a_cloud() {
    let mut pts = Pts::default();
    let tris = box_surface(
        &mut pts,
        [0.0, 0.0, 0.0],
        [100.0, 100.0, 1.0],
        [30, 30, 1],
        false,
    );
    let mut p = pts.p.clone();
    let mut r = Rng(11);
    // Points keep a distance of at least 1 from the box's surface, as interior points of
    // a mesher do (seed paper: "not too close to an existing face"): inside, only near the
    // mid-plane.
    for _ in 0..600 {
        let q = [
            -20.0 + 140.0 * r.f(),
            -20.0 + 140.0 * r.f(),
            -10.0 + 21.0 * r.f(),
        ];
        let dist = |x: f64, lo: f64, hi: f64| {
            if x < lo {
                lo - x
            } else if x > hi {
                x - hi
            } else {
                0.0
            }
        };
        let (dx, dy, dz) = (
            dist(q[0], 0.0, 100.0),
            dist(q[1], 0.0, 100.0),
            dist(q[2], 0.0, 1.0),
        );
        let inside = dx == 0.0 && dy == 0.0 && dz == 0.0;
        let d = if inside {
            q[0].min(100.0 - q[0])
                .min(q[1])
                .min(100.0 - q[1])
                .min(q[2])
                .min(1.0 - q[2])
        } else {
            (dx * dx + dy * dy + dz * dz).sqrt()
        };
        if d >= 1.0 {
            p.push(q);
        }
    }
    let (rep, missing) = recover_and_check(&p, &tris, "thin box");
    assert!(missing > 0);
    assert!(rep.steiner_on_edges > 0, "{rep:?}");
    // Every one is taken off the surface again (the input triangles come back).
    assert_eq!(rep.steiner_left_on_surface, 0, "{rep:?}");
}

/// Two cubes sharing a face: the shared face is an interface, its boundary edges are used
/// by three (or four) triangles.
#[test]
fn two_cubes_sharing_a_face() {
    let mut pts = Pts::default();
    let mut tris = box_surface(&mut pts, [0.0; 3], [1.0; 3], [4, 4, 4], false);
    tris.extend(box_surface(
        &mut pts,
        [1.0, 0.0, 0.0],
        [2.0, 1.0, 1.0],
        [4, 4, 4],
        true,
    ));
    let mut p = pts.p.clone();
    p.extend(
        random(300, 6)
            .into_iter()
            .map(|q| [-0.5 + 3.0 * q[0], -0.5 + 2.0 * q[1], -0.5 + 2.0 * q[2]]),
    );
    let (rep, missing) = recover_and_check(&p, &tris, "two cubes");
    assert!(missing > 0);
    assert!(rep.flips > 0);
    // Steiner points on the interface's edges too (three or four triangles on a segment).
    assert!(rep.steiner_on_edges > 0, "{rep:?}");
    assert_eq!(rep.steiner_left_on_surface, 0, "{rep:?}");
}

/// An open tilted square sheet (a wake) inside a box, with points around it.
#[test]
fn open_sheet_inside_a_box() {
    let mut pts = Pts::default();
    let mut tris = box_surface(&mut pts, [0.0; 3], [1.0; 3], [4, 4, 4], false);
    let n = 6;
    let at = |i: usize, j: usize| {
        let (x, y) = (
            0.2 + 0.6 * i as f64 / n as f64,
            0.2 + 0.6 * j as f64 / n as f64,
        );
        [x, y, 0.35 + 0.3 * x]
    };
    for i in 0..n {
        for j in 0..n {
            let c = [
                pts.id(at(i, j)),
                pts.id(at(i + 1, j)),
                pts.id(at(i + 1, j + 1)),
                pts.id(at(i, j + 1)),
            ];
            tris.push([c[0], c[1], c[2]]);
            tris.push([c[0], c[2], c[3]]);
        }
    }
    let mut p = pts.p.clone();
    let mut r = Rng(13);
    for _ in 0..300 {
        let q = [
            0.02 + 0.96 * r.f(),
            0.02 + 0.96 * r.f(),
            0.02 + 0.96 * r.f(),
        ];
        if (q[2] - 0.35 - 0.3 * q[0]).abs() > 0.03 {
            p.push(q);
        }
    }
    let (rep, missing) = recover_and_check(&p, &tris, "sheet");
    assert!(missing > 0);
    assert!(rep.flips > 0);
}

/// About 100k surface triangles (a 91 × 91 grid per cube face) with 30k points around:
/// `cargo test --release --no-default-features --test recover -- --ignored large`.
#[test]
#[ignore]
fn large_cube_surface() {
    let mut pts = Pts::default();
    let tris = box_surface(&mut pts, [0.0; 3], [1.0; 3], [91, 91, 91], false);
    let mut p = pts.p.clone();
    p.extend(
        random(30000, 8)
            .into_iter()
            .map(|q| q.map(|x| -0.2 + 1.4 * x)),
    );
    let t = std::time::Instant::now();
    let (rep, missing) = recover_and_check(&p, &tris, "large cube");
    eprintln!(
        "large: {missing} missing edges, {rep:?}, {:.2} s total",
        t.elapsed().as_secs_f64()
    );
}

#[test]
fn hull_edge_removal_square_pyramid() {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.5, 0.5, 1.0],
    ];
    let mut d = triangulate(&p).unwrap();
    let (a, b, c, e) = if d.has_edge(0, 2) {
        (0, 2, 1, 3)
    } else {
        (1, 3, 0, 2)
    };
    let (_, ring) = d.tets_around_edge(a, b).unwrap();
    eprintln!("ring of {a}-{b}: {ring:?}");
    let r = d.remove_edge(a, b, quality);
    eprintln!("{r:?}");
    r.unwrap();
    d.check_valid().unwrap();
    assert!(d.has_edge(c, e) && !d.has_edge(a, b));
}

/// Embedded segments (free edges inside the volume): long wires through a cloud of points,
/// which the Delaunay tetrahedralisation misses, become edges (split by Steiner points where
/// flips cannot, suppressed again where a cone from a segment end allows).
#[test]
fn embedded_segments_through_a_cloud() {
    let mut pts = Pts::default();
    let tris = box_surface(&mut pts, [0.0; 3], [1.0; 3], [4, 4, 4], false);
    let mut p = pts.p.clone();
    let wires = [
        ([0.1, 0.15, 0.2], [0.9, 0.85, 0.8]),
        ([0.85, 0.1, 0.3], [0.15, 0.9, 0.6]),
        ([0.5, 0.05, 0.95], [0.45, 0.95, 0.05]),
    ];
    let mut segments = Vec::new();
    for (a, b) in wires {
        let i = p.len() as u32;
        p.push(a);
        p.push(b);
        segments.push([i, i + 1]);
    }
    let mut r = Rng(31);
    while p.len() < 500 {
        p.push([
            0.03 + 0.94 * r.f(),
            0.03 + 0.94 * r.f(),
            0.03 + 0.94 * r.f(),
        ]);
    }
    let mut d = triangulate(&p).unwrap();
    let missing = segments.iter().filter(|s| !d.has_edge(s[0], s[1])).count();
    assert_eq!(
        missing,
        segments.len(),
        "every wire should cut through the cloud"
    );
    let mut out = tris.clone();
    let (mut parent, mut segs, mut seg_parent) = (Vec::new(), segments.clone(), Vec::new());
    let rep =
        recover_boundary_and_segments(&mut d, &mut out, &mut parent, &mut segs, &mut seg_parent)
            .unwrap();
    eprintln!("wires: {rep:?}, {} segment pieces", segs.len());
    d.check_valid().unwrap();
    assert!(rep.flips > 0);
    assert_eq!(seg_parent.len(), segs.len());
    // The pieces of each wire chain from one end to the other along the wire.
    for (k, s) in segments.iter().enumerate() {
        let pieces: Vec<[u32; 2]> = segs
            .iter()
            .zip(&seg_parent)
            .filter(|(_, &q)| q == k as u32)
            .map(|(s, _)| *s)
            .collect();
        let (a, b) = (d.point(s[0]), d.point(s[1]));
        let len = |x: [f64; 3], y: [f64; 3]| {
            ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
        };
        let total: f64 = pieces
            .iter()
            .map(|q| len(d.point(q[0]), d.point(q[1])))
            .sum();
        assert!(
            (total - len(a, b)).abs() < 1e-12 * len(a, b),
            "wire {k} pieces off the line"
        );
        for q in &pieces {
            assert!(d.has_edge(q[0], q[1]), "wire {k} piece {q:?} missing");
        }
    }
    if rep.steiner_left_on_surface == 0 {
        assert_eq!(segs, segments);
    }
    for t in &out {
        assert!(d.find_face_near(t[0], t[1], t[2]).is_some());
    }
}

/// A wing root's chord on a symmetry plane (the hull): the plane holds the chord `AB`, a
/// node of the other surface just across it (`U`, inside the chord's diametral circle) and
/// straight columns of layer points under both ends, so the Delaunay plane is a fan from
/// `U` to the columns and the flips from the chord's ends meet quads whose corners are
/// collinear (the column). The chord and its thin layer triangle come back by flips of the
/// crossing hull edges taken in queue order, without a Steiner point.
#[test]
fn chord_beside_layer_columns_on_a_hull_plane_is_recovered_by_flips() {
    let mut p: Vec<[f64; 3]> = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.45, 0.03, 0.0]];
    let (a, b) = (0u32, 1u32);
    let mut h = 2e-5;
    for _ in 0..12 {
        p.push([0.0, -h, 0.0]);
        p.push([1.0, -h * 1.01, 0.0]);
        h *= 1.5;
    }
    // Points above the plane (the wing's surface and the volume beyond it).
    let mut r = Rng(0x5eed_1234);
    for _ in 0..40 {
        p.push([1.2 * r.f() - 0.1, 0.3 * r.f() - 0.15, 0.05 + 0.5 * r.f()]);
    }
    let mut d = triangulate(&p).unwrap();
    assert!(
        !d.has_edge(a, b),
        "the test wants the chord missing from the Delaunay"
    );
    // The chord's first layer triangle (A, B, B1).
    let mut tris = vec![[a, b, 4]];
    let mut parent = vec![0];
    let rep = recover_boundary(&mut d, &mut tris, &mut parent).unwrap();
    d.check_valid().unwrap();
    assert_eq!(rep.steiner_on_edges + rep.steiner_on_faces, 0, "{rep:?}");
    assert!(d.has_edge(a, b));
    assert!(d.find_face_near(a, b, 4).is_some());
}
