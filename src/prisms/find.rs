//! The candidate prisms: three tets on three columns of one stage at two consecutive levels
//! that fill the prism those six points span (bottom, top, and each side quad cut by one
//! diagonal), with every split of the prism positive.

use super::shape;
use crate::mesh::{LayerTag, VolumeMesh};
use rayon::prelude::*;

/// Three tets that fill a prism.
#[derive(Clone, Debug)]
pub(super) struct Candidate {
    pub tets: [u32; 3],
    /// `[b0, b1, b2, t0, t1, t2]` in the mesh's prism order.
    pub nodes: [u32; 6],
    pub region: u32,
    pub level: u32,
    /// Per side quad (columns 0–1, 1–2, 2–0): its two triangles as the tets cut it.
    pub sides: [[[u32; 3]; 2]; 3],
}

/// What the search saw.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Found {
    /// Groups of three tets on a prism's six points that do not fill it.
    pub not_filling: usize,
    /// Prisms some split of which has a tet that is not positive.
    pub bad_shape: usize,
}

/// The prism key of a tet: lower level, stage, source, side and the three column roots.
type Key = (u32, u16, u16, bool, [u32; 3]);

/// The key of a tet whose four points are layer points, or why it has none.
fn key_of(tags: [LayerTag; 4]) -> Result<Key, &'static str> {
    let t0 = tags[0];
    if tags.iter().any(|t| t.stage != t0.stage) {
        return Err("two stages");
    }
    if tags.iter().any(|t| t.source != t0.source) {
        return Err("two sources");
    }
    let lo = tags.iter().map(|t| t.level).min().unwrap_or(0);
    let hi = tags.iter().map(|t| t.level).max().unwrap_or(0);
    match hi - lo {
        0 => return Err("one level"),
        1 => {}
        _ => return Err("levels apart"),
    }
    let mut roots = tags.map(|t| t.root);
    roots.sort_unstable();
    let [a, b, c, d] = roots;
    let three = match (a == b, b == c, c == d) {
        (true, false, false) => [a, c, d],
        (false, true, false) => [a, b, d],
        (false, false, true) => [a, b, c],
        (false, false, false) => return Err("four columns"),
        _ => return Err("two columns"),
    };
    // A root is level 0 of the columns on both sides of a two-sided source: the side is the
    // upper points'.
    let below = tags.iter().any(|t| t.below);
    Ok((lo, t0.stage, t0.source, below, three))
}

/// The layer tags of a tet's four points, if all are layer points.
fn tags_of(mesh: &VolumeMesh, t: [u32; 4]) -> Option<[LayerTag; 4]> {
    let tag = |v: u32| mesh.point_layer.get(v as usize).copied().flatten();
    Some([tag(t[0])?, tag(t[1])?, tag(t[2])?, tag(t[3])?])
}

pub(super) fn candidates(mesh: &VolumeMesh) -> (Vec<Candidate>, Found) {
    let mut keyed: Vec<(Key, u32)> = (0..mesh.tets.len())
        .into_par_iter()
        .filter_map(|k| Some((key_of(tags_of(mesh, mesh.tets[k])?).ok()?, k as u32)))
        .collect();
    let mut found = Found::default();
    keyed.par_sort_unstable();
    let groups: Vec<&[(Key, u32)]> = keyed.chunk_by(|a, b| a.0 == b.0).collect();
    if log::log_enabled!(log::Level::Debug) {
        debug_unkeyed(mesh, &groups);
    }
    let made: Vec<Result<Candidate, Refusal>> = groups
        .par_iter()
        .filter(|g| g.len() == 3)
        .map(|g| fill(mesh, g[0].0, [g[0].1, g[1].1, g[2].1]))
        .collect();
    let mut out = Vec::with_capacity(made.len());
    for m in made {
        match m {
            Ok(c) => out.push(c),
            Err(Refusal::NotFilling) => found.not_filling += 1,
            Err(Refusal::Shape) => found.bad_shape += 1,
        }
    }
    // In the order of the keys: level by level, and within a level by the columns' roots,
    // which follow the surface mesh's node order (as the layers' column order does). The
    // conforming choice is greedy: it must not depend on how the kernel stored the tets.
    (out, found)
}

/// Debug: why layer tets of one stage have no prism key, per stage; the tets by the size of
/// their key's group (three fill a prism).
fn debug_unkeyed(mesh: &VolumeMesh, groups: &[&[(Key, u32)]]) {
    let mut why: std::collections::BTreeMap<(u16, &str), usize> = Default::default();
    for &t in &mesh.tets {
        let Some(tags) = tags_of(mesh, t) else {
            continue;
        };
        match key_of(tags) {
            Err("two stages") | Ok(_) => {}
            Err(reason) => *why.entry((tags[0].stage, reason)).or_default() += 1,
        }
    }
    let mut sizes: std::collections::BTreeMap<usize, usize> = Default::default();
    for g in groups {
        *sizes.entry(g.len().min(5)).or_default() += g.len();
    }
    log::debug!("prisms: layer tets in no key: {why:?}; tets by key group size: {sizes:?}");
}

/// The stage whose layers hold every point of a cell.
pub(super) fn layer_stage(mesh: &VolumeMesh, cell: &[u32]) -> Option<u16> {
    let tag = |v: u32| mesh.point_layer.get(v as usize).copied().flatten();
    let first = tag(cell[0])?;
    cell.iter()
        .all(|&v| tag(v).is_some_and(|t| t.stage == first.stage))
        .then_some(first.stage)
}

/// A triangle's corners in increasing order: its key as a face.
pub(super) fn sorted(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

enum Refusal {
    NotFilling,
    Shape,
}

/// The prism the three tets of `key` fill, if they fill one.
fn fill(mesh: &VolumeMesh, key: Key, tets: [u32; 3]) -> Result<Candidate, Refusal> {
    let (level, _, _, _, roots) = key;
    let region = mesh.tet_region[tets[0] as usize];
    if tets.iter().any(|&t| mesh.tet_region[t as usize] != region) {
        return Err(Refusal::NotFilling);
    }
    // The node of each column at each of the two levels, one node per place.
    let mut at = [[u32::MAX; 3]; 2];
    for &t in &tets {
        for v in mesh.tets[t as usize] {
            let Some(tag) = mesh.point_layer[v as usize] else {
                return Err(Refusal::NotFilling);
            };
            let (Some(c), l) = (roots.iter().position(|&r| r == tag.root), tag.level - level)
            else {
                return Err(Refusal::NotFilling);
            };
            let slot = &mut at[l as usize][c];
            if *slot != u32::MAX && *slot != v {
                return Err(Refusal::NotFilling);
            }
            *slot = v;
        }
    }
    if at.iter().flatten().any(|&v| v == u32::MAX) {
        return Err(Refusal::NotFilling);
    }
    // The faces of the three tets met once: bottom, top and two per side quad.
    let mut faces: Vec<[u32; 3]> = Vec::with_capacity(12);
    for &t in &tets {
        let v = mesh.tets[t as usize];
        for f in crate::mesh::validity::OUTWARD_FACES {
            faces.push(f.map(|i| v[i]));
        }
    }
    let keys: Vec<[u32; 3]> = faces.iter().map(|&f| sorted(f)).collect();
    let outer: Vec<[u32; 3]> = (0..faces.len())
        .filter(|&i| keys.iter().filter(|&&k| k == keys[i]).count() == 1)
        .map(|i| faces[i])
        .collect();
    let [b, t] = at;
    if outer.len() != 8 || !keys_contain(&outer, sorted(b)) || !keys_contain(&outer, sorted(t)) {
        return Err(Refusal::NotFilling);
    }
    let mut sides = [[[0u32; 3]; 2]; 3];
    for (s, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
        let quad = [b[i], b[j], t[i], t[j]];
        let on: Vec<[u32; 3]> = (outer.iter())
            .filter(|f| f.iter().all(|v| quad.contains(v)))
            .copied()
            .collect();
        let [x, y] = on[..] else {
            return Err(Refusal::NotFilling);
        };
        sides[s] = [x, y];
    }
    // Bottom counter-clockwise seen from the top: swap two columns when it is not.
    let mut nodes = [b[0], b[1], b[2], t[0], t[1], t[2]];
    let p = nodes.map(|v| mesh.points[v as usize]);
    if crate::mesh::quality::volume_sign([p[0], p[1], p[2], p[3]]) < 0.0 {
        nodes = [b[0], b[2], b[1], t[0], t[2], t[1]];
        sides = [sides[2], sides[1], sides[0]];
    }
    if !shape::prism_is_valid(&nodes.map(|v| mesh.points[v as usize])) {
        return Err(Refusal::Shape);
    }
    Ok(Candidate {
        tets,
        nodes,
        region,
        level,
        sides,
    })
}

fn keys_contain(faces: &[[u32; 3]], key: [u32; 3]) -> bool {
    faces.iter().any(|&f| sorted(f) == key)
}
