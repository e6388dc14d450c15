//! The advancing front of one face: directed segments with the unmeshed part of the face on
//! their left, a queue that hands out the shortest segment first, and two spatial indexes —
//! front vertices in 3-D (candidate search) and segment boxes in (u,v) (crossing tests).

use super::boundary::FaceVertex;
use glam::DVec2;
use rstar::{primitives::GeomWithData, primitives::Rectangle, RTree, AABB};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

type VertexPoint = GeomWithData<[f64; 3], usize>;
type SegmentBox = GeomWithData<Rectangle<[f64; 2]>, usize>;

/// Ordered f64 for the queue (lengths are finite and non-negative).
#[derive(Clone, Copy, PartialEq)]
struct Len(f64);
impl PartialOrd for Len {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Eq for Len {}
impl Ord for Len {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

pub struct Front {
    pub vertices: Vec<FaceVertex>,
    segments: Vec<[usize; 2]>,
    alive: Vec<bool>,
    /// Live segment by its (start, end).
    by_ends: HashMap<(usize, usize), usize>,
    /// Number of live segments at each vertex.
    degree: Vec<u32>,
    /// Live segments at each vertex.
    incident: Vec<Vec<usize>>,
    queue: BinaryHeap<Reverse<(Len, u32, usize)>>,
    /// How often each segment was tried without success.
    pub failures: Vec<u32>,
    points: RTree<VertexPoint>,
    boxes: RTree<SegmentBox>,
    live: usize,
}

impl Front {
    /// The front of `segments`; one running back along another cancels it (the two sides of a
    /// closed gap), except on a `slit`, whose both sides the mesh must reach.
    pub fn new(vertices: Vec<FaceVertex>, segments: &[[usize; 2]], slits: &[[usize; 2]]) -> Self {
        let mut f = Front {
            degree: vec![0; vertices.len()],
            incident: vec![Vec::new(); vertices.len()],
            vertices,
            segments: Vec::new(),
            alive: Vec::new(),
            by_ends: HashMap::new(),
            queue: BinaryHeap::new(),
            failures: Vec::new(),
            points: RTree::new(),
            boxes: RTree::new(),
            live: 0,
        };
        for s in segments {
            if slits.contains(s) {
                f.add(s[0], s[1]);
            } else {
                f.add_or_cancel(s[0], s[1]);
            }
        }
        f
    }

    pub fn is_empty(&self) -> bool {
        self.live == 0
    }

    pub fn segment(&self, s: usize) -> [usize; 2] {
        self.segments[s]
    }

    pub fn add_vertex(&mut self, v: FaceVertex) -> usize {
        self.vertices.push(v);
        self.degree.push(0);
        self.incident.push(Vec::new());
        self.vertices.len() - 1
    }

    fn seg_box(&self, s: usize) -> SegmentBox {
        let [a, b] = self.segments[s];
        let (p, q) = (self.vertices[a].uv, self.vertices[b].uv);
        GeomWithData::new(
            Rectangle::from_corners(p.min(q).to_array(), p.max(q).to_array()),
            s,
        )
    }

    fn point_of(&self, v: usize) -> VertexPoint {
        GeomWithData::new(self.vertices[v].xyz.to_array(), v)
    }

    /// Add segment a→b, or cancel it against b→a when that is on the front (the two sides of
    /// a closed gap). Returns whether a segment was added.
    pub fn add_or_cancel(&mut self, a: usize, b: usize) -> bool {
        if let Some(&s) = self.by_ends.get(&(b, a)) {
            self.remove(s);
            false
        } else {
            self.add(a, b);
            true
        }
    }

    fn add(&mut self, a: usize, b: usize) {
        let s = self.segments.len();
        self.segments.push([a, b]);
        self.alive.push(true);
        self.failures.push(0);
        self.by_ends.insert((a, b), s);
        for v in [a, b] {
            self.incident[v].push(s);
            self.degree[v] += 1;
            if self.degree[v] == 1 {
                self.points.insert(self.point_of(v));
            }
        }
        self.boxes.insert(self.seg_box(s));
        self.push(s);
        self.live += 1;
    }

    /// Queue segment `s` (again), shortest first, fewer failures first.
    pub fn push(&mut self, s: usize) {
        let [a, b] = self.segments[s];
        let len = self.vertices[a].xyz.distance(self.vertices[b].xyz);
        self.queue.push(Reverse((Len(len), self.failures[s], s)));
    }

    pub fn remove(&mut self, s: usize) {
        if !self.alive[s] {
            return;
        }
        self.alive[s] = false;
        let [a, b] = self.segments[s];
        self.by_ends.remove(&(a, b));
        self.boxes.remove(&self.seg_box(s));
        for v in [a, b] {
            self.incident[v].retain(|&x| x != s);
            self.degree[v] -= 1;
            if self.degree[v] == 0 {
                self.points.remove(&self.point_of(v));
            }
        }
        self.live -= 1;
    }

    /// The next live segment: the shortest, preferring ones that failed less.
    pub fn pop(&mut self) -> Option<usize> {
        while let Some(Reverse((_, fails, s))) = self.queue.pop() {
            if self.alive[s] && fails == self.failures[s] {
                return Some(s);
            }
        }
        None
    }

    /// All live segments (for debugging output).
    pub fn live_segments(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.segments.len()).filter(|&s| self.alive[s])
    }

    pub fn is_alive(&self, s: usize) -> bool {
        self.alive[s]
    }

    /// Give segment `s` a fresh start: no failures, queued again.
    pub fn reset(&mut self, s: usize) {
        self.failures[s] = 0;
        self.push(s);
    }

    pub fn find(&self, a: usize, b: usize) -> Option<usize> {
        self.by_ends.get(&(a, b)).copied()
    }

    /// Vertices joined to `v` by a live segment.
    pub fn neighbours(&self, v: usize) -> impl Iterator<Item = usize> + '_ {
        self.incident[v].iter().map(move |&s| {
            let [p, q] = self.segments[s];
            if p == v {
                q
            } else {
                p
            }
        })
    }

    /// Front vertices within `radius` of `p` in 3-D.
    pub fn vertices_near(&self, p: glam::DVec3, radius: f64) -> Vec<usize> {
        self.points
            .locate_within_distance(p.to_array(), radius * radius)
            .map(|g| g.data)
            .collect()
    }

    /// Live segments whose (u,v) box meets the box of `pts`.
    pub fn segments_near(&self, pts: &[DVec2]) -> Vec<usize> {
        let lo = pts.iter().fold(DVec2::INFINITY, |m, p| m.min(*p));
        let hi = pts.iter().fold(DVec2::NEG_INFINITY, |m, p| m.max(*p));
        self.boxes
            .locate_in_envelope_intersecting(&AABB::from_corners(lo.to_array(), hi.to_array()))
            .map(|g| g.data)
            .collect()
    }
}
