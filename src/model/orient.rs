//! Automatic orientation, as in the seed paper: loops by the sign of their parametric area
//! (largest |area| is the outer loop), faces in a shell by agreement along shared edges, and
//! shells by the sign of their enclosed volume (largest is the outer shell, others cavities).

use super::{EntityRef, FaceIntegrals, Loop, Model, Shell};
use rayon::prelude::*;
use std::collections::HashMap;

/// Why a model could not be oriented.
#[derive(Debug, thiserror::Error)]
pub enum OrientError {
    #[error("{0}: a boundary point could not be placed in the face's parameter plane (the edge does not lie on the surface?)")]
    Unplaceable(EntityRef),
    #[error("{0}: the faces of a shell cannot be oriented consistently (a Möbius-like shell, or faces that meet along {1} the wrong way)")]
    Inconsistent(EntityRef, EntityRef),
    #[error("{0}: shell encloses no volume (open or flat)")]
    ZeroVolume(EntityRef),
}

/// What orientation found, per face.
#[derive(Clone, Debug, Default)]
pub struct Orientation {
    pub integrals: Vec<Option<FaceIntegrals>>,
}

impl Model {
    /// Orient every loop, face and shell; see the module comment.
    pub fn orient(&mut self) -> Result<Orientation, OrientError> {
        // Loops first: only their (u,v) polygons are needed.
        for f in 0..self.faces.len() {
            if self.faces[f].loops.iter().all(|l| l.uses.is_empty()) {
                continue;
            }
            let polys = self
                .loop_polygons(f)
                .ok_or_else(|| OrientError::Unplaceable(self.face_ref(f)))?;
            let areas: Vec<f64> = polys
                .iter()
                .map(|p| super::integrals::signed_area(p))
                .collect();
            orient_loops(&mut self.faces[f].loops, &areas);
        }
        // Then the face integrals with the loops in their final direction, faces in parallel.
        let integrals: Vec<Option<FaceIntegrals>> = (0..self.faces.len())
            .into_par_iter()
            .map(|f| self.face_integrals(f))
            .collect();
        for r in 0..self.regions.len() {
            let mut shells = std::mem::take(&mut self.regions[r].shells);
            for shell in &mut shells {
                self.orient_shell(shell, &integrals, r)?;
            }
            // Largest volume first: the outer shell; the others are cavities, whose normals
            // must point into the cavity, away from the region.
            shells.sort_by(|a, b| b.volume.total_cmp(&a.volume));
            for cavity in shells.iter_mut().skip(1) {
                for fu in &mut cavity.faces {
                    fu.reversed = !fu.reversed;
                }
            }
            self.regions[r].shells = shells;
        }
        Ok(Orientation { integrals })
    }

    /// Make the faces of one shell agree along shared edges, then point them outwards.
    fn orient_shell(
        &self,
        shell: &mut Shell,
        integrals: &[Option<FaceIntegrals>],
        region: usize,
    ) -> Result<(), OrientError> {
        // Direction (+1/−1) in which each face's loops run along each edge; a seam (used twice by
        // one face) says nothing about the neighbours and is skipped.
        let mut uses: HashMap<usize, Vec<(usize, i8)>> = HashMap::new();
        for (k, fu) in shell.faces.iter().enumerate() {
            let mut seen: HashMap<usize, i8> = HashMap::new();
            for lp in &self.faces[fu.face].loops {
                for u in lp
                    .uses
                    .iter()
                    .filter(|u| !self.edges[u.edge].is_degenerate())
                {
                    let dir = if u.reversed { -1 } else { 1 };
                    if seen.insert(u.edge, dir).is_some() {
                        seen.insert(u.edge, 0);
                    }
                }
            }
            for (e, dir) in seen.into_iter().filter(|&(_, d)| d != 0) {
                uses.entry(e).or_default().push((k, dir));
            }
        }
        // Breadth-first propagation of signs s_k (true = keep the surface normal).
        let n = shell.faces.len();
        let mut sign: Vec<Option<bool>> = vec![None; n];
        let mut by_face: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (&e, list) in &uses {
            for &(k, _) in list {
                by_face[k].push(e);
            }
        }
        for start in 0..n {
            if sign[start].is_some() {
                continue;
            }
            sign[start] = Some(true);
            let mut queue = std::collections::VecDeque::from([start]);
            while let Some(k) = queue.pop_front() {
                let sk = sign[k].unwrap_or(true);
                for &e in &by_face[k] {
                    let list = &uses[&e];
                    if list.len() != 2 {
                        continue;
                    }
                    let (mine, other) = if list[0].0 == k {
                        (list[0], list[1])
                    } else {
                        (list[1], list[0])
                    };
                    // Consistent when the two faces run along the edge in opposite directions.
                    let want = if mine.1 == other.1 { !sk } else { sk };
                    match sign[other.0] {
                        None => {
                            sign[other.0] = Some(want);
                            queue.push_back(other.0);
                        }
                        Some(s) if s != want => {
                            return Err(OrientError::Inconsistent(
                                self.face_ref(shell.faces[other.0].face),
                                self.edge_ref(e),
                            ))
                        }
                        _ => {}
                    }
                }
            }
        }
        let volume: f64 = shell
            .faces
            .iter()
            .zip(&sign)
            .map(|(fu, s)| {
                let flux = integrals[fu.face].as_ref().map_or(0.0, |i| i.flux);
                if s.unwrap_or(true) {
                    flux
                } else {
                    -flux
                }
            })
            .sum();
        if volume == 0.0 || !volume.is_finite() {
            return Err(OrientError::ZeroVolume(self.region_ref(region)));
        }
        let outward = volume > 0.0;
        for (fu, s) in shell.faces.iter_mut().zip(&sign) {
            fu.reversed = s.unwrap_or(true) != outward;
        }
        shell.volume = volume.abs();
        Ok(())
    }
}

/// Outer loop (largest |area|) first and counter-clockwise, holes clockwise.
fn orient_loops(loops: &mut Vec<Loop>, areas: &[f64]) {
    let mut with_area: Vec<(Loop, f64)> = Vec::new();
    let mut rest = Vec::new();
    let mut areas = areas.iter();
    for lp in loops.drain(..) {
        if lp.uses.is_empty() {
            rest.push(lp);
        } else {
            with_area.push((lp, *areas.next().unwrap_or(&0.0)));
        }
    }
    with_area.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
    for (k, (lp, area)) in with_area.iter_mut().enumerate() {
        let want_ccw = k == 0;
        if (*area > 0.0) != want_ccw {
            reverse_loop(lp);
        }
    }
    loops.extend(with_area.into_iter().map(|(l, _)| l));
    loops.extend(rest);
}

/// Run a loop the other way.
pub fn reverse_loop(lp: &mut Loop) {
    lp.uses.reverse();
    for u in &mut lp.uses {
        u.reversed = !u.reversed;
    }
}
