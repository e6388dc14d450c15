//! Distance profile between two edges of one face: for samples of edge A, the nearest sample of
//! edge B in 3-D, with both (u,v). Usage: pinch_profile FILE FACE EDGE_A EDGE_B [N]
#[cfg(feature = "occt")]
fn main() {
    use tetrafoil::case::case_from_cad;
    let args: Vec<String> = std::env::args().skip(1).collect();
    let case = case_from_cad(std::path::Path::new(&args[0])).unwrap_or_else(|e| panic!("{e}"));
    let model = &case.model;
    let f: usize = args[1].parse().unwrap();
    let ea: usize = args[2].parse().unwrap();
    let eb: usize = args[3].parse().unwrap();
    let n: usize = args.get(4).map_or(60, |a| a.parse().unwrap());
    let face = &model.faces[f];
    let find = |e: usize| {
        face.loops
            .iter()
            .flat_map(|l| l.uses.iter())
            .find(|u| u.edge == e)
            .unwrap()
    };
    let (ua, ub) = (find(ea), find(eb));
    let sample = |u: &tetrafoil::model::EdgeUse, m: usize| {
        let e = &model.edges[u.edge];
        (0..=m)
            .map(|i| {
                let t = e.range.0 + (e.range.1 - e.range.0) * i as f64 / m as f64;
                (
                    t,
                    model.edge_point(u.edge, t),
                    model.use_uv(f, u, t).unwrap(),
                )
            })
            .collect::<Vec<_>>()
    };
    let b = sample(ub, 20000);
    let mut len = 0.0;
    let a = sample(ua, n);
    for (i, (t, p, uv)) in a.iter().enumerate() {
        if i > 0 {
            len += p.distance(a[i - 1].1);
        }
        let (tb, pb, uvb) = b
            .iter()
            .min_by(|x, y| x.1.distance(*p).total_cmp(&y.1.distance(*p)))
            .unwrap();
        println!(
            "A t {t:10.4} s {len:8.3} uv ({:9.5},{:9.5}) | B t {tb:10.4} uv ({:9.5},{:9.5}) | 3-D {:.3e}",
            uv.x,
            uv.y,
            uvb.x,
            uvb.y,
            p.distance(*pb)
        );
    }
}

#[cfg(not(feature = "occt"))]
fn main() {
    eprintln!("needs the occt feature");
}
