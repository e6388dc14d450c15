//! The crate's own cxx bridge to the C++ shim in `cpp/`. Raw and unsafe to share: the safe
//! types in the rest of the crate own these objects and decide how they cross threads.

#[cxx::bridge(namespace = "tfo")]
pub(crate) mod bridge {
    struct VertexRec {
        x: f64,
        y: f64,
        z: f64,
        tolerance: f64,
    }

    struct EdgeRec {
        v0: i32,
        v1: i32,
        degenerate: bool,
        has_curve: bool,
        first: f64,
        last: f64,
        tolerance: f64,
    }

    struct FaceRec {
        name: String,
        has_name: bool,
        surface_kind: String,
        reversed: bool,
        u0: f64,
        u1: f64,
        v0: f64,
        v1: f64,
        u_periodic: bool,
        v_periodic: bool,
        u_period: f64,
        v_period: f64,
        tolerance: f64,
    }

    struct UseRec {
        face: i32,
        loop_index: i32,
        edge: i32,
        reversed: bool,
        seam: bool,
    }

    struct ShellFaceRec {
        shell: i32,
        face: i32,
        reversed: bool,
    }

    struct SolidRec {
        name: String,
        has_name: bool,
    }

    struct SolidShellRec {
        solid: i32,
        shell: i32,
    }

    #[derive(Default)]
    struct Topology {
        vertices: Vec<VertexRec>,
        edges: Vec<EdgeRec>,
        faces: Vec<FaceRec>,
        uses: Vec<UseRec>,
        shell_count: i32,
        /// Shells whose OCCT `Closed` flag is unset (e.g. a STEP OPEN_SHELL).
        shells_flagged_open: Vec<i32>,
        shell_faces: Vec<ShellFaceRec>,
        solids: Vec<SolidRec>,
        solid_shells: Vec<SolidShellRec>,
    }

    #[derive(Default, Debug, Clone, Copy, PartialEq, Eq)]
    struct SewStats {
        free_edges: i32,
        multiple_edges: i32,
        degenerated: i32,
        closed_shells: i32,
        open_shells: i32,
        solids_made: i32,
    }

    /// What the lofted-body construction made: OCCT's volumes of the parts (summed) and of
    /// the body, its faces and how many lie on the symmetry plane.
    #[derive(Default, Debug, Clone, Copy, PartialEq)]
    struct BodyStats {
        parts_volume: f64,
        volume: f64,
        faces: i32,
        symmetry_faces: i32,
    }

    /// What the wing-in-box construction made.
    #[derive(Default, Debug, Clone, Copy, PartialEq)]
    struct BuildStats {
        wing_volume: f64,
        fluid_volume: f64,
        faces: i32,
        wing_faces: i32,
        symmetry_faces: i32,
    }

    unsafe extern "C++" {
        include!("tetrafoil-occt/cpp/shim.hxx");

        #[namespace = ""]
        type TopoDS_Shape = opencascade_sys::topo_ds::TopoDS_Shape;

        type ShapeIndex;
        type SurfaceGeom;
        type CurveGeom;
        type PcurveGeom;

        /// Stops OCCT's default messenger printing reader chatter to stdout (process-wide, once).
        fn quiet_messages();
        fn read_step_xde(path: &str, status: &mut i32) -> Result<UniquePtr<ShapeIndex>>;
        fn index_shape(shape: &TopoDS_Shape) -> Result<UniquePtr<ShapeIndex>>;
        /// kind: 0 vertex, 1 edge, 2 face, 3 shell, 4 solid, other: the whole shape.
        fn sub_shape(idx: &ShapeIndex, kind: i32, i: i32) -> Result<UniquePtr<TopoDS_Shape>>;

        fn extract_topology(idx: &ShapeIndex, out: &mut Topology) -> Result<()>;

        fn sew_shape(
            idx: &ShapeIndex,
            tolerance: f64,
            stats: &mut SewStats,
        ) -> Result<UniquePtr<ShapeIndex>>;
        fn heal_shape(idx: &ShapeIndex, tolerance: f64) -> Result<UniquePtr<ShapeIndex>>;
        /// General fuse of all solids (contacts imprinted and shared); `fuzzy` 0 for exact.
        fn fuse_solids(idx: &ShapeIndex, fuzzy: f64) -> Result<UniquePtr<ShapeIndex>>;
        /// The solids alone, without the faces and shells that lie beside them.
        fn solids_only(idx: &ShapeIndex) -> Result<UniquePtr<ShapeIndex>>;
        /// A box (kind 0) or sphere (1: radius `half[0]`) about `centre` with the body's solids
        /// cut out; `axis` ≥ 0 keeps the side of the plane coord[axis] = `plane` that `side`'s
        /// sign says. Faces named "farfield", "symmetry" or as the body's.
        #[allow(clippy::too_many_arguments)]
        fn farfield_domain(
            body: &ShapeIndex,
            kind: i32,
            centre: &[f64],
            half: &[f64],
            axis: i32,
            plane: f64,
            side: i32,
            fuzzy: f64,
        ) -> Result<UniquePtr<ShapeIndex>>;

        fn face_surface(idx: &ShapeIndex, face: i32) -> Result<UniquePtr<SurfaceGeom>>;
        fn surface_clone(g: &SurfaceGeom) -> Result<UniquePtr<SurfaceGeom>>;
        fn surface_info(g: &SurfaceGeom, out: &mut [f64]);
        fn surface_d2(g: &SurfaceGeom, u: f64, v: f64, out: &mut [f64]) -> Result<()>;
        fn surface_project(
            g: Pin<&mut SurfaceGeom>,
            p: &[f64],
            has_hint: bool,
            out: &mut [f64],
        ) -> Result<bool>;
        fn surface_intersect_circle(g: &SurfaceGeom, c: &[f64]) -> Result<Vec<f64>>;

        fn edge_curve(idx: &ShapeIndex, edge: i32) -> Result<UniquePtr<CurveGeom>>;
        fn curve_clone(g: &CurveGeom) -> Result<UniquePtr<CurveGeom>>;
        fn curve_range(g: &CurveGeom, out: &mut [f64]);
        fn curve_d2(g: &CurveGeom, t: f64, out: &mut [f64]) -> Result<()>;
        fn curve_project(
            g: &CurveGeom,
            p: &[f64],
            has_hint: bool,
            hint: f64,
            out: &mut [f64],
        ) -> Result<bool>;

        fn use_pcurve(
            idx: &ShapeIndex,
            face: i32,
            loop_index: i32,
            edge_use: i32,
        ) -> Result<UniquePtr<PcurveGeom>>;
        fn pcurve_clone(g: &PcurveGeom) -> Result<UniquePtr<PcurveGeom>>;
        fn pcurve_range(g: &PcurveGeom, out: &mut [f64]);
        fn pcurve_d2(g: &PcurveGeom, t: f64, out: &mut [f64]) -> Result<()>;

        fn adaptive_measure(idx: &ShapeIndex, kind: i32, i: i32, eps: f64) -> Result<f64>;

        fn wing_in_box(
            points: &[f64],
            counts: &[i32],
            bounds: &[f64],
            path: &str,
            stats: &mut BuildStats,
        ) -> Result<()>;

        fn loose_polygons(points: &[f64], counts: &[i32], path: &str) -> Result<()>;

        #[allow(clippy::too_many_arguments)]
        fn lofted_body(
            points: &[f64],
            counts: &[i32],
            sections_per_part: &[i32],
            part_flags: &[i32],
            tips: &[f64],
            names: &str,
            half: bool,
            path: &str,
            stats: &mut BodyStats,
        ) -> Result<()>;
    }
}

// SAFETY: each of these C++ objects owns deep copies of its OCCT geometry (made with
// Geom_*::Copy in the shim) that no other object references, so nothing is shared across
// threads by moving one. Copy is deep for composite geometry too (checked against OCCT 7.8.1:
// the copies of revolution/extrusion/offset/trimmed surfaces and trimmed curves hold new basis
// objects). OCCT handle reference counts are atomic and the objects use no thread-local state.
// They are not `Sync`: the safe wrappers put each behind its own Mutex.
unsafe impl Send for bridge::SurfaceGeom {}
unsafe impl Send for bridge::CurveGeom {}
unsafe impl Send for bridge::PcurveGeom {}
