//! Which faces pass near a point: per face, the closest point of its surface (unbounded), its
//! (u,v), distance and unit normal. Usage: near_point FILE X Y Z
#[cfg(feature = "occt")]
fn main() {
    use tetrafoil::case::case_from_cad;
    let args: Vec<String> = std::env::args().skip(1).collect();
    let case = case_from_cad(std::path::Path::new(&args[0])).unwrap_or_else(|e| panic!("{e}"));
    let x: Vec<f64> = args[1..4].iter().map(|a| a.parse().unwrap()).collect();
    let p = glam::DVec3::new(x[0], x[1], x[2]);
    for (f, face) in case.model.faces.iter().enumerate() {
        if let Some(uv) = face.surface.closest_uv(p, None) {
            let q = face.surface.point(uv);
            let n = face.surface.normal(uv).normalize_or_zero();
            println!(
                "face {f}: uv {uv:?} at {q:?} distance {:.4e} normal {n:?}",
                q.distance(p)
            );
        }
    }
}

#[cfg(not(feature = "occt"))]
fn main() {}
