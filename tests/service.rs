//! The mesh service end to end: the `tetrafoil serve` binary on a loopback port with a
//! temporary data folder, driven over HTTP. Samples and a corpus STEP file mesh to `done`
//! through the event stream, and their SU2 and VTU results are read back and checked; a
//! server killed with SIGKILL mid-job and restarted finishes every job exactly once; bad
//! requests get a clear 4xx JSON error; cancel, the bounded queue and the time limit work.

mod common;

use common::server::{root, scratch, Server};

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};
use tetrafoil::mesh::{validity, Marker, VolumeMesh};

use serde_json::Value;

/// One multipart part: field name, file name, bytes.
type Part<'a> = (&'a str, Option<&'a str>, Vec<u8>);

fn multipart(parts: &[Part<'_>]) -> (String, Vec<u8>) {
    let boundary = "test-boundary-5c1f0e".to_string();
    let mut body = Vec::new();
    for (name, file, bytes) in parts {
        body.extend_from_slice(format!("--{boundary}\r\n").as_bytes());
        let d = match file {
            Some(f) => format!("form-data; name=\"{name}\"; filename=\"{f}\""),
            None => format!("form-data; name=\"{name}\""),
        };
        body.extend_from_slice(format!("Content-Disposition: {d}\r\n\r\n").as_bytes());
        body.extend_from_slice(bytes);
        body.extend_from_slice(b"\r\n");
    }
    body.extend_from_slice(format!("--{boundary}--\r\n").as_bytes());
    (boundary, body)
}

/// Status and JSON body of any answer (4xx/5xx included).
fn answer(r: Result<ureq::Response, ureq::Error>) -> (u16, Value) {
    let response = match r {
        Ok(r) => r,
        Err(ureq::Error::Status(_, r)) => r,
        Err(e) => panic!("transport error: {e}"),
    };
    let status = response.status();
    let text = response.into_string().expect("body");
    let json = serde_json::from_str(&text).unwrap_or(Value::String(text));
    (status, json)
}

fn post(server: &Server, token: Option<&str>, parts: &[Part<'_>]) -> (u16, Value) {
    let (boundary, body) = multipart(parts);
    let mut r = ureq::post(&server.url("/v1/jobs")).set(
        "Content-Type",
        &format!("multipart/form-data; boundary={boundary}"),
    );
    if let Some(t) = token {
        r = r.set("Authorization", &format!("Bearer {t}"));
    }
    answer(r.send_bytes(&body))
}

fn get(server: &Server, token: Option<&str>, path: &str) -> (u16, Value) {
    let mut r = ureq::get(&server.url(path));
    if let Some(t) = token {
        r = r.set("Authorization", &format!("Bearer {t}"));
    }
    answer(r.call())
}

fn submit(server: &Server, parts: &[Part<'_>]) -> String {
    let (status, job) = post(server, None, parts);
    assert_eq!(status, 201, "submission refused: {job}");
    job["id"].as_str().expect("job id").to_string()
}

fn case_part(sample: &str) -> Part<'static> {
    let path = root().join("samples").join(sample).join("case.toml");
    let text = std::fs::read(&path).expect("sample case");
    ("case", Some("case.toml"), text)
}

/// Every event of a job, from its SSE stream, to the end of the job.
fn follow(server: &Server, id: &str) -> Vec<Value> {
    let response = ureq::get(&server.url(&format!("/v1/jobs/{id}/events")))
        .timeout(Duration::from_secs(120))
        .call()
        .expect("event stream");
    let mut events = Vec::new();
    for line in BufReader::new(response.into_reader()).lines() {
        let line = line.expect("event line");
        if let Some(data) = line.strip_prefix("data:") {
            let e: Value = serde_json::from_str(data.trim()).expect("event JSON");
            let end = matches!(e["kind"].as_str(), Some("done" | "failed" | "cancelled"));
            events.push(e);
            if end {
                break;
            }
        }
    }
    events
}

fn kinds<'a>(events: &'a [Value], kind: &str) -> Vec<&'a Value> {
    events.iter().filter(|e| e["kind"] == kind).collect()
}

fn download(server: &Server, id: &str, format: &str) -> Vec<u8> {
    let r = ureq::get(&server.url(&format!("/v1/jobs/{id}/result/{format}")))
        .call()
        .unwrap_or_else(|e| panic!("result {format} of {id}: {e}"));
    let mut bytes = Vec::new();
    r.into_reader()
        .read_to_end(&mut bytes)
        .expect("result bytes");
    bytes
}

/// An SU2 file read back as a volume mesh (regions from its `% region` comments).
fn read_su2(text: &str) -> VolumeMesh {
    let mut m = VolumeMesh::default();
    let mut lines = text.lines();
    let mut ranges = Vec::new();
    let count = |l: &str| {
        l.split('=')
            .nth(1)
            .unwrap()
            .trim()
            .parse::<usize>()
            .unwrap()
    };
    while let Some(line) = lines.next() {
        let line = line.trim();
        if let Some(rest) = line.strip_prefix("% region ") {
            let (head, range) = rest.split_once(": elements ").unwrap();
            let name = head.split_once(' ').unwrap().1.to_string();
            let (a, b) = range.split_once(" to ").unwrap();
            ranges.push((
                name,
                a.parse::<usize>().unwrap(),
                b.parse::<usize>().unwrap(),
            ));
        } else if line.starts_with("NELEM=") {
            for _ in 0..count(line) {
                let w: Vec<u32> = lines
                    .next()
                    .unwrap()
                    .split_whitespace()
                    .map(|x| x.parse().unwrap())
                    .collect();
                assert_eq!(w[0], 10, "a tetrahedron");
                m.tets.push([w[1], w[2], w[3], w[4]]);
            }
        } else if line.starts_with("NPOIN=") {
            for _ in 0..count(line) {
                let w: Vec<f64> = lines
                    .next()
                    .unwrap()
                    .split_whitespace()
                    .map(|x| x.parse().unwrap())
                    .collect();
                m.points.push(glam::DVec3::new(w[0], w[1], w[2]));
            }
        } else if let Some(name) = line.strip_prefix("MARKER_TAG=") {
            let n = count(lines.next().unwrap());
            let marker = m.markers.len() as u32;
            m.markers.push(Marker {
                id: marker as usize,
                name: name.trim().to_string(),
            });
            for _ in 0..n {
                let w: Vec<u32> = lines
                    .next()
                    .unwrap()
                    .split_whitespace()
                    .map(|x| x.parse().unwrap())
                    .collect();
                assert_eq!(w[0], 5, "a triangle");
                m.boundary.push([w[1], w[2], w[3]]);
                m.boundary_marker.push(marker);
            }
        }
    }
    m.tet_region = vec![0; m.tets.len()];
    for (r, (name, a, b)) in ranges.iter().enumerate() {
        m.regions.push(Marker {
            id: r,
            name: name.clone(),
        });
        for k in *a..=*b {
            m.tet_region[k] = r as u32;
        }
    }
    if m.regions.is_empty() {
        m.regions.push(Marker {
            id: 0,
            name: "region_0".into(),
        });
    }
    m
}

/// A finished job's SU2 and VTU: the SU2 passes the validity check with the job's markers,
/// the VTU has the same tets, every one positive.
fn check_results(server: &Server, id: &str, what: &str) {
    let (_, job) = get(server, None, &format!("/v1/jobs/{id}"));
    assert_eq!(job["state"], "done", "{what}: {job}");
    let report = &job["report"]["mesh"];
    let tets = report["tets"].as_u64().unwrap() as usize;
    let su2 = String::from_utf8(download(server, id, "su2")).expect("SU2 text");
    let mesh = read_su2(&su2);
    assert_eq!(mesh.tets.len(), tets, "{what}: SU2 tets");
    let validity = validity::check(&mesh);
    assert!(
        validity.is_valid(),
        "{what}: SU2 mesh invalid: {:?}",
        validity.defects
    );
    let mut expected: Vec<String> = report["markers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| tetrafoil::io::clean_name(m.as_str().unwrap()))
        .collect();
    expected.sort();
    expected.dedup();
    let mut got: Vec<String> = mesh.markers.iter().map(|m| m.name.clone()).collect();
    got.sort();
    assert_eq!(got, expected, "{what}: SU2 markers");
    let vtu = download(server, id, "vtu");
    let path = server.data.with_extension(format!("{id}.vtu"));
    std::fs::write(&path, vtu).expect("vtu copy");
    let cells = tetrafoil::io::vtk::read(&path).expect("VTU reads");
    let vtu_tets: Vec<&Vec<usize>> = cells.cells.iter().filter(|c| c.len() == 4).collect();
    assert_eq!(vtu_tets.len(), tets, "{what}: VTU tets");
    for c in vtu_tets {
        let p = |k: usize| cells.points[c[k]];
        let v = (p(1) - p(0)).dot((p(2) - p(0)).cross(p(3) - p(0)));
        assert!(v > 0.0, "{what}: a VTU tet of volume {v}");
    }
}

#[test]
fn samples_and_a_cad_file_mesh_through_the_service() {
    let data = scratch("samples");
    let server = Server::start(&data, &["--workers", "2", "--threads-per-job", "1"]);
    let mut jobs: Vec<(String, String)> = Vec::new();
    for sample in ["cube", "cube_cavity", "turbine", "wing"] {
        jobs.push((sample.into(), submit(&server, &[case_part(sample)])));
    }
    // Directional refinement from one face, asked in the submission.
    let refine = [
        case_part("cube"),
        ("refine_faces", None, b"xmin".to_vec()),
        ("first", None, b"0.01".to_vec()),
    ];
    jobs.push(("cube refined".into(), submit(&server, &refine)));
    // The same, grouped into prisms by the case file's `[mesh] prisms = true`.
    let cube = std::fs::read_to_string(root().join("samples/cube/case.toml")).unwrap();
    let case = cube
        .replacen("size = ", "prisms = true\nsize = ", 1)
        .into_bytes();
    let prisms = [
        ("case", Some("case.toml"), case),
        ("refine_faces", None, b"zmin".to_vec()),
        ("first", None, b"0.004".to_vec()),
        ("formats", None, b"su2,msh,ugrid".to_vec()),
    ];
    let prisms_job = submit(&server, &prisms);
    // STEP through the OpenCASCADE plugin (common::occt).
    let step = std::fs::read(root().join("samples/wing_step/wing_in_box.step")).unwrap();
    let geometry = ("geometry", Some("wing_in_box.step"), step);
    jobs.push(("wing_step".into(), submit(&server, &[geometry])));
    if let Some(path) = common::corpus::corpus_file("tet_rhino.step") {
        let bytes = std::fs::read(path).unwrap();
        // The same file through a case naming it, with a spacing of its own.
        let case = "[mesh]\ncad = \"tet_rhino.step\"\n".as_bytes().to_vec();
        let parts = [
            ("geometry", Some("tet_rhino.step"), bytes),
            ("case", Some("tet.toml"), case),
            ("formats", None, b"su2,vtu,stl".to_vec()),
        ];
        jobs.push(("tet_rhino.step".into(), submit(&server, &parts)));
    }
    for (what, id) in &jobs {
        let events = follow(&server, id);
        assert_eq!(kinds(&events, "done").len(), 1, "{what}: one done event");
        let stages: Vec<&str> = kinds(&events, "stage")
            .iter()
            .filter_map(|e| e["stage"].as_str())
            .collect();
        for stage in ["load", "curves", "surfaces", "volume", "write"] {
            assert!(
                stages.contains(&stage),
                "{what}: stage {stage} in {stages:?}"
            );
        }
        let surface = kinds(&events, "progress")
            .into_iter()
            .filter(|e| e["stage"] == "surfaces")
            .filter_map(|e| e["total"].as_u64())
            .max();
        assert!(
            surface.is_some_and(|n| n >= 1),
            "{what}: surface progress counts faces"
        );
        check_results(&server, id, what);
        let (_, job) = get(&server, None, &format!("/v1/jobs/{id}"));
        let refined = job["report"]["refinement"]["stages"]
            .as_array()
            .map(Vec::len);
        assert_eq!(
            refined.is_some(),
            what == "cube refined",
            "{what}: {refined:?}"
        );
    }
    // The prisms job: its report counts them, its SU2 holds them (type 13) and its boundary
    // quads (type 9).
    let events = follow(&server, &prisms_job);
    assert_eq!(kinds(&events, "done").len(), 1, "prisms: {events:?}");
    assert!(kinds(&events, "stage")
        .iter()
        .any(|e| e["stage"] == "prisms"));
    let (_, job) = get(&server, None, &format!("/v1/jobs/{prisms_job}"));
    let report = &job["report"];
    let count = report["mesh"]["prisms"].as_u64().unwrap_or(0);
    assert!(count > 1000, "{}", report["prisms"]);
    assert_eq!(report["prisms"]["prisms"].as_u64(), Some(count));
    let su2 = String::from_utf8(download(&server, &prisms_job, "su2")).unwrap();
    let lines = |kind: &str| su2.lines().filter(|l| l.starts_with(kind)).count() as u64;
    assert_eq!(lines("13 "), count);
    assert_eq!(
        lines("9 "),
        report["mesh"]["boundary_quads"].as_u64().unwrap()
    );
    // UGRID's first line: nodes, triangles, quads, tets, pyramids, prisms, hexes.
    let ugrid = String::from_utf8(download(&server, &prisms_job, "ugrid")).unwrap();
    let head: Vec<u64> = (ugrid.lines().next().unwrap().split(' '))
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(head[5], count, "{head:?}");
    assert_eq!(Some(head[2]), report["mesh"]["boundary_quads"].as_u64());
    // Its .mapbc: a line per marker (the cube's six walls), FUN3D's wall code.
    let mapbc = String::from_utf8(download(&server, &prisms_job, "ugrid/mapbc")).unwrap();
    let markers = report["mesh"]["markers"].as_array().unwrap().len();
    assert_eq!(mapbc.lines().next(), Some(markers.to_string().as_str()));
    assert_eq!(mapbc.lines().count(), markers + 1, "{mapbc}");
    assert!(
        mapbc.lines().skip(1).all(|l| l.contains(" 4000 ")),
        "{mapbc}"
    );
    let (status, said) = get(
        &server,
        None,
        &format!("/v1/jobs/{prisms_job}/result/su2/mapbc"),
    );
    assert_eq!(status, 404);
    assert!(said.to_string().contains("UGRID"), "{said}");
    jobs.push(("cube prisms".into(), prisms_job));
    let (status, list) = get(&server, None, "/v1/jobs");
    assert_eq!(status, 200);
    assert_eq!(list["jobs"].as_array().unwrap().len(), jobs.len());
    let metrics = ureq::get(&server.url("/metrics"))
        .call()
        .unwrap()
        .into_string()
        .unwrap();
    assert!(
        metrics.contains(&format!("tetrafoil_jobs{{state=\"done\"}} {}", jobs.len())),
        "{metrics}"
    );
    assert!(metrics.contains("tetrafoil_stage_runs_total{stage=\"surfaces\"}"));
}

#[test]
fn a_killed_server_reruns_its_jobs_exactly_once() {
    let data = scratch("restart");
    let server = Server::start(&data, &["--workers", "1", "--threads-per-job", "2"]);
    let wing = submit(&server, &[case_part("wing")]);
    let cube = submit(&server, &[case_part("cube")]);
    let cavity = submit(&server, &[case_part("cube_cavity")]);
    // Wait until the wing is inside its volume stage, then kill the server.
    let start = Instant::now();
    loop {
        let (_, job) = get(&server, None, &format!("/v1/jobs/{wing}"));
        if job["state"] == "running" && job["progress"]["stage"] == "interior" {
            break;
        }
        assert_ne!(job["state"], "done", "the wing finished before the kill");
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "the wing never ran"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let server = server.kill_and_restart();
    for (what, id) in [("wing", &wing), ("cube", &cube), ("cube_cavity", &cavity)] {
        let events = follow(&server, id);
        assert_eq!(kinds(&events, "done").len(), 1, "{what}: done exactly once");
        assert_eq!(kinds(&events, "failed").len(), 0, "{what}: {events:?}");
        check_results(&server, id, what);
    }
    let (_, job) = get(&server, None, &format!("/v1/jobs/{wing}"));
    assert_eq!(
        job["attempts"], 2,
        "the wing ran again from the start: {job}"
    );
    let events = follow(&server, &wing);
    assert_eq!(kinds(&events, "requeued").len(), 1);
    // The partial files of the killed run are gone: only whole results are left.
    let out = data.join("jobs").join(&wing).join("out");
    let mut names: Vec<String> = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "mesh-su2.su2",
            "mesh-vtu.vtu",
            "report.json",
            "surface.json"
        ]
    );
    // A finished job is not run again by a second restart.
    let server = server.kill_and_restart();
    std::thread::sleep(Duration::from_millis(300));
    let (_, job) = get(&server, None, &format!("/v1/jobs/{cube}"));
    assert_eq!(
        (job["state"].as_str(), job["attempts"].as_u64()),
        (Some("done"), Some(1))
    );
}

const TOKEN_A: &str = "alice-0123456789abcdef";
const TOKEN_B: &str = "bob-fedcba9876543210";

fn error_of(answer: &(u16, Value)) -> String {
    answer.1["error"].as_str().unwrap_or("").to_string()
}

#[test]
fn bad_requests_get_a_clear_4xx() {
    let data = scratch("bad");
    let tokens = data.with_extension("tokens");
    std::fs::write(
        &tokens,
        format!("# test tokens\nalice {TOKEN_A}\nbob {TOKEN_B}\n"),
    )
    .unwrap();
    let tokens = tokens.to_str().unwrap().to_string();
    let server = Server::start(&data, &["--token-file", &tokens, "--workers", "1"]);
    let a = Some(TOKEN_A);
    let cube = || case_part("cube");

    // Tokens: none, wrong, and another owner's job.
    let r = post(&server, None, &[cube()]);
    assert_eq!(r.0, 401, "{r:?}");
    let r = post(&server, Some("not-a-token-at-all"), &[cube()]);
    assert_eq!(r.0, 401, "{r:?}");
    assert!(error_of(&r).contains("unknown token"));
    let r = post(&server, a, &[cube()]);
    assert_eq!(r.0, 201, "{r:?}");
    let id = r.1["id"].as_str().unwrap().to_string();
    assert_eq!(
        get(&server, Some(TOKEN_B), &format!("/v1/jobs/{id}")).0,
        404
    );
    assert_eq!(
        get(&server, Some(TOKEN_B), "/v1/jobs").1["jobs"]
            .as_array()
            .unwrap()
            .len(),
        0
    );
    assert_eq!(get(&server, a, &format!("/v1/jobs/{id}")).0, 200);

    // No file at all.
    let r = post(&server, a, &[("size", None, b"0.5".to_vec())]);
    assert_eq!(r.0, 400, "{r:?}");
    assert!(error_of(&r).contains("no file"), "{r:?}");
    // Not multipart.
    let r = answer(
        ureq::post(&server.url("/v1/jobs"))
            .set("Authorization", &format!("Bearer {TOKEN_A}"))
            .send_string("hello"),
    );
    assert_eq!(r.0, 400, "{r:?}");
    // An unknown format, at submission and at download.
    let r = post(
        &server,
        a,
        &[cube(), ("formats", None, b"su2,xyz".to_vec())],
    );
    assert_eq!(r.0, 400, "{r:?}");
    assert!(error_of(&r).contains("unknown format 'xyz'"), "{r:?}");
    let r = get(&server, a, &format!("/v1/jobs/{id}/result/xyz"));
    assert_eq!(r.0, 400, "{r:?}");
    // Refinement without its first spacing, and with a growth below 1.
    let r = post(
        &server,
        a,
        &[cube(), ("refine_faces", None, b"xmin".to_vec())],
    );
    assert_eq!(r.0, 400, "{r:?}");
    assert!(error_of(&r).contains("first"), "{r:?}");
    let parts = [
        cube(),
        ("refine_faces", None, b"xmin".to_vec()),
        ("first", None, b"0.01".to_vec()),
        ("growth", None, b"0.5".to_vec()),
    ];
    let r = post(&server, a, &parts);
    assert_eq!(r.0, 400, "{r:?}");
    assert!(
        error_of(&r).contains("growth must be a number >= 1"),
        "{r:?}"
    );
    // Not a CAD file by its name.
    let r = post(&server, a, &[("geometry", Some("part.exe"), vec![0; 8])]);
    assert_eq!(r.0, 400, "{r:?}");

    // Path traversal and absolute paths in a case's `cad`.
    let step = b"ISO-10303-21;".to_vec();
    for cad in ["../../x.step", "/etc/x.step", "sub/x.step", "..\\\\x.step"] {
        let case = format!("# a case\n[mesh]\ncad = \"{cad}\"\n").into_bytes();
        let parts = [
            ("geometry", Some("x.step"), step.clone()),
            ("case", Some("c.toml"), case),
        ];
        let r = post(&server, a, &parts);
        assert_eq!(r.0, 400, "{cad}: {r:?}");
        assert_eq!(r.1["key"], "mesh.cad", "{cad}: {r:?}");
        assert_eq!(r.1["line"], 3, "{cad}: {r:?}");
        assert!(
            error_of(&r).contains("not a bare file name"),
            "{cad}: {r:?}"
        );
    }
    // A malformed case: the error names the key and line.
    let case = b"[mesh]\ntolerance = 1e-6\nsize = \"big\"\n".to_vec();
    let r = post(&server, a, &[("case", Some("c.toml"), case)]);
    assert_eq!(r.0, 400, "{r:?}");
    assert_eq!(
        (r.1["key"].as_str(), r.1["line"].as_u64()),
        (Some("size"), Some(3)),
        "{r:?}"
    );
    let case = b"[mesh]\nsize = 0.1\nsizee = 2\n".to_vec();
    let r = post(&server, a, &[("case", Some("c.toml"), case)]);
    assert_eq!((r.0, r.1["line"].as_u64()), (400, Some(3)), "{r:?}");
    assert!(error_of(&r).contains("sizee"), "{r:?}");

    // A 2 GiB upload is refused from its header, before the body is sent.
    let mut tcp = TcpStream::connect(("127.0.0.1", server.port)).unwrap();
    tcp.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    let head = format!(
        "POST /v1/jobs HTTP/1.1\r\nHost: 127.0.0.1\r\nAuthorization: Bearer {TOKEN_A}\r\n\
         Content-Type: multipart/form-data; boundary=x\r\nContent-Length: {}\r\n\r\n",
        2u64 << 30
    );
    let start = Instant::now();
    tcp.write_all(head.as_bytes()).unwrap();
    tcp.write_all(&[b'a'; 4096]).unwrap();
    let mut reply = [0u8; 512];
    let n = tcp.read(&mut reply).unwrap();
    let reply = String::from_utf8_lossy(&reply[..n]);
    assert!(reply.starts_with("HTTP/1.1 413"), "{reply}");
    assert!(reply.contains("at most"), "{reply}");
    assert!(start.elapsed() < Duration::from_secs(5));

    // Unknown routes and jobs.
    assert_eq!(get(&server, a, "/v1/nothing").0, 404);
    assert_eq!(get(&server, a, "/v1/jobs/../../etc/passwd").0, 404);
    assert_eq!(get(&server, a, "/v1/jobs/0123456789abcdef").0, 404);
    // The service stays up through all of it.
    assert_eq!(get(&server, None, "/healthz").0, 200);
}

/// The message of the one `failed` event of job `id`, once its events end.
fn failure_of(server: &Server, id: &str) -> String {
    let events = follow(server, id);
    let failed = kinds(&events, "failed");
    assert_eq!(failed.len(), 1, "{events:?}");
    failed[0]["message"].as_str().unwrap_or("").to_string()
}

#[test]
fn cancel_queue_bound_and_time_limit() {
    let data = scratch("limits");
    let args = [
        "--workers",
        "1",
        "--threads-per-job",
        "1",
        "--max-queue",
        "1",
    ];
    let server = Server::start(&data, &args);
    // The wing runs; the turbine waits (the one place in the queue); a third is refused.
    let wing = submit(&server, &[case_part("wing")]);
    let start = Instant::now();
    while get(&server, None, &format!("/v1/jobs/{wing}")).1["state"] != "running" {
        assert!(start.elapsed() < Duration::from_secs(30));
        std::thread::sleep(Duration::from_millis(20));
    }
    let turbine = submit(&server, &[case_part("turbine")]);
    let r = post(&server, None, &[case_part("cube")]);
    assert_eq!(r.0, 429, "{r:?}");
    // Cancel both: the queued one at once, the running one at its next check.
    let del = |id: &str| answer(ureq::delete(&server.url(&format!("/v1/jobs/{id}"))).call());
    assert_eq!(del(&turbine).0, 202);
    assert_eq!(del(&wing).0, 202);
    let events = follow(&server, &wing);
    assert_eq!(kinds(&events, "cancelled").len(), 1, "{events:?}");
    let (_, job) = get(&server, None, &format!("/v1/jobs/{turbine}"));
    assert_eq!(job["state"], "cancelled");
    assert_eq!(
        get(&server, None, &format!("/v1/jobs/{wing}/result/su2")).0,
        409
    );
    // A finished job is deleted with its files.
    assert_eq!(del(&wing).0, 204);
    assert_eq!(get(&server, None, &format!("/v1/jobs/{wing}")).0, 404);
    assert!(!data.join("jobs").join(&wing).exists());
    drop(server);

    // The time limit fails a run that passes it.
    let data = scratch("time-limit");
    let server = Server::start(&data, &["--workers", "1", "--time-limit", "1"]);
    let wing = submit(&server, &[case_part("wing")]);
    let message = failure_of(&server, &wing);
    assert!(message.contains("time limit"), "{message}");
    let cube = submit(&server, &[case_part("cube")]);
    assert_eq!(kinds(&follow(&server, &cube), "done").len(), 1);
    drop(server);

    // The memory limit fails a run that holds more than it (the wing holds over 100 MiB);
    // a run within it reports its peak.
    let data = scratch("memory-limit");
    let server = Server::start(&data, &["--workers", "1", "--memory-limit", "20"]);
    let wing = submit(&server, &[case_part("wing")]);
    let message = failure_of(&server, &wing);
    assert!(message.contains("memory limit of 20 MiB"), "{message}");
    let out = data.join("jobs").join(&wing).join("out");
    let left = std::fs::read_dir(&out).map_or(0, |d| d.count());
    assert_eq!(left, 0, "partial results left in {}", out.display());
    let cube = submit(&server, &[case_part("cube")]);
    assert_eq!(kinds(&follow(&server, &cube), "done").len(), 1);
    let (_, job) = get(&server, None, &format!("/v1/jobs/{cube}"));
    let peak = job["report"]["memory_peak_mib"].as_f64().unwrap_or(0.0);
    assert!(peak > 0.1 && peak < 20.0, "{peak} MiB");
    // A mistyped size is refused from the estimate before anything is meshed.
    let typo = submit(
        &server,
        &[case_part("wing"), ("size", None, b"1e-7".to_vec())],
    );
    let message = failure_of(&server, &typo);
    assert!(message.contains("tetrahedra"), "{message}");
    assert!(message.contains("uniform size 1e-7"), "{message}");
}

#[test]
fn the_submit_command_waits_and_downloads() {
    let data = scratch("submit");
    let server = Server::start(&data, &["--workers", "1", "--threads-per-job", "1"]);
    let (su2, vtu) = (data.join("cube.su2"), data.join("cube.vtu"));
    let run = |args: &[&std::ffi::OsStr]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
            .arg("submit")
            .args(args)
            .arg("--server")
            .arg(server.url(""))
            .output()
            .expect("tetrafoil submit")
    };
    let case = root().join("samples/cube/case.toml");
    let out = run(&[
        case.as_os_str(),
        "-o".as_ref(),
        su2.as_os_str(),
        "-o".as_ref(),
        vtu.as_os_str(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let id = String::from_utf8_lossy(&out.stdout).trim().to_string();
    assert!(stderr.contains(&format!("{id}: surfaces")), "{stderr}");
    let mesh = read_su2(&std::fs::read_to_string(&su2).expect("SU2 written"));
    assert!(validity::check(&mesh).is_valid());
    let cells = tetrafoil::io::vtk::read(&vtu).expect("VTU written");
    assert_eq!(
        cells.cells.iter().filter(|c| c.len() == 4).count(),
        mesh.tets.len()
    );
    // A failing job: the command says why and exits non-zero.
    let bad = data.join("bad.toml");
    std::fs::write(
        &bad,
        "[mesh]\nsize = 0.5\n\n[[vertex]]\nname = \"a\"\npoint = [0, 0, 0]\n",
    )
    .unwrap();
    let out = run(&[bad.as_os_str(), "--wait".as_ref()]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("failed"), "{stderr}");
    // A refused one: the server's message.
    let out = run(&[bad.as_os_str(), "--size=-1".as_ref()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("400"), "{stderr}");
}
