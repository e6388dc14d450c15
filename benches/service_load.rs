//! Load test of `tetrafoil serve`, loopback only, bounded, stopping by itself: 200 submissions
//! of small cases (the cube and cube-with-cavity samples) from 20 concurrent clients. Each
//! client submits, polls its job until it ends, and downloads the SU2 result; every API call
//! is timed. Prints per call kind the count, p50, p99 and max latency while the meshing runs,
//! the error responses (there must be none), and the wall time; exits non-zero if a job did
//! not finish `done` or any call failed.
//!
//! ```sh
//! cargo bench --bench service_load            # release build
//! cargo bench --bench service_load -- 40 4    # 40 submissions from 4 clients
//! ```

use std::io::Read;
use std::net::TcpListener;
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

/// The whole run stops here whatever happens.
const DEADLINE: Duration = Duration::from_secs(600);

#[derive(Default)]
struct Stats {
    calls: Vec<(&'static str, f64)>,
    errors: Vec<String>,
    done: usize,
    not_done: Vec<String>,
}

fn timed<T>(stats: &Mutex<Stats>, kind: &'static str, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let out = f();
    let ms = start.elapsed().as_secs_f64() * 1e3;
    stats.lock().unwrap().calls.push((kind, ms));
    out
}

fn multipart(case: &[u8]) -> (String, Vec<u8>) {
    let boundary = "load-test-boundary".to_string();
    let mut body = Vec::new();
    body.extend_from_slice(format!("--{boundary}\r\n").as_bytes());
    body.extend_from_slice(
        b"Content-Disposition: form-data; name=\"case\"; filename=\"case.toml\"\r\n\r\n",
    );
    body.extend_from_slice(case);
    body.extend_from_slice(format!("\r\n--{boundary}\r\n").as_bytes());
    body.extend_from_slice(b"Content-Disposition: form-data; name=\"formats\"\r\n\r\nsu2\r\n");
    body.extend_from_slice(format!("--{boundary}--\r\n").as_bytes());
    (boundary, body)
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let k = ((sorted.len() as f64 - 1.0) * p).round() as usize;
    sorted[k.min(sorted.len() - 1)]
}

fn client(base: &str, cases: &[Vec<u8>], jobs: &[usize], stats: &Mutex<Stats>, start: Instant) {
    for &k in jobs {
        let (boundary, body) = multipart(&cases[k % cases.len()]);
        let sent = timed(stats, "POST /v1/jobs", || {
            ureq::post(&format!("{base}/v1/jobs"))
                .set(
                    "Content-Type",
                    &format!("multipart/form-data; boundary={boundary}"),
                )
                .send_bytes(&body)
                .map_err(|e| e.to_string())
        });
        let id = match sent.map(|r| r.into_string()) {
            Ok(Ok(text)) => {
                let v: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
                v["id"].as_str().unwrap_or_default().to_string()
            }
            Ok(Err(e)) => {
                stats
                    .lock()
                    .unwrap()
                    .errors
                    .push(format!("submit body: {e}"));
                continue;
            }
            Err(e) => {
                stats.lock().unwrap().errors.push(format!("submit: {e}"));
                continue;
            }
        };
        let state = loop {
            if start.elapsed() > DEADLINE {
                break "deadline".to_string();
            }
            let r = timed(stats, "GET /v1/jobs/{id}", || {
                ureq::get(&format!("{base}/v1/jobs/{id}"))
                    .call()
                    .map_err(|e| e.to_string())
            });
            let state = match r.map(|r| r.into_string()) {
                Ok(Ok(text)) => {
                    let v: serde_json::Value = serde_json::from_str(&text).unwrap_or_default();
                    v["state"].as_str().unwrap_or("?").to_string()
                }
                Ok(Err(e)) => format!("unreadable: {e}"),
                Err(e) => {
                    stats.lock().unwrap().errors.push(format!("poll {id}: {e}"));
                    break "error".into();
                }
            };
            if state != "queued" && state != "running" {
                break state;
            }
            std::thread::sleep(Duration::from_millis(100));
        };
        if state != "done" {
            stats
                .lock()
                .unwrap()
                .not_done
                .push(format!("{id}: {state}"));
            continue;
        }
        let r = timed(stats, "GET /v1/jobs/{id}/result/su2", || {
            ureq::get(&format!("{base}/v1/jobs/{id}/result/su2"))
                .call()
                .map(|r| {
                    let mut bytes = Vec::new();
                    let _ = r.into_reader().read_to_end(&mut bytes);
                    bytes.len()
                })
                .map_err(|e| e.to_string())
        });
        match r {
            Ok(n) if n > 0 => stats.lock().unwrap().done += 1,
            Ok(_) => stats
                .lock()
                .unwrap()
                .errors
                .push(format!("{id}: empty result")),
            Err(e) => stats
                .lock()
                .unwrap()
                .errors
                .push(format!("result {id}: {e}")),
        }
    }
}

fn main() {
    // `cargo bench` passes `--bench`; numbers are the submissions and clients.
    let numbers: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let submissions = numbers.first().copied().unwrap_or(200);
    let clients = numbers.get(1).copied().unwrap_or(20).max(1);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let data = root.join("target/service-load");
    let _ = std::fs::remove_dir_all(&data);
    std::fs::create_dir_all(&data).expect("data folder");
    let port = TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let mut server = Command::new(env!("CARGO_BIN_EXE_tetrafoil"))
        .args(["--quiet", "serve", "--data"])
        .arg(&data)
        .args(["--listen", &format!("127.0.0.1:{port}")])
        .args(["--workers", "2", "--threads-per-job", "1"])
        .args(["--max-queue", &(submissions + 1).to_string()])
        .stdin(Stdio::null())
        .spawn()
        .expect("starting tetrafoil serve");
    let base = format!("http://127.0.0.1:{port}");
    let up = Instant::now();
    while ureq::get(&format!("{base}/healthz")).call().is_err() {
        assert!(
            up.elapsed() < Duration::from_secs(20),
            "the server did not come up"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    let cases: Vec<Vec<u8>> = ["cube", "cube_cavity"]
        .iter()
        .map(|s| std::fs::read(root.join("samples").join(s).join("case.toml")).unwrap())
        .collect();
    let stats = Mutex::new(Stats::default());
    let start = Instant::now();
    std::thread::scope(|scope| {
        for c in 0..clients {
            let jobs: Vec<usize> = (0..submissions).filter(|k| k % clients == c).collect();
            let (base, cases, stats) = (&base, &cases, &stats);
            scope.spawn(move || client(base, cases, &jobs, stats, start));
        }
    });
    let wall = start.elapsed().as_secs_f64();
    let _ = server.kill();
    let _ = server.wait();
    let stats = stats.into_inner().unwrap();
    println!("{submissions} submissions from {clients} clients, 2 workers × 1 thread: {wall:.1} s");
    let mut kinds: Vec<&str> = stats.calls.iter().map(|c| c.0).collect();
    kinds.sort();
    kinds.dedup();
    for kind in kinds {
        let mut ms: Vec<f64> = stats
            .calls
            .iter()
            .filter(|c| c.0 == kind)
            .map(|c| c.1)
            .collect();
        ms.sort_by(f64::total_cmp);
        println!(
            "{kind:<32} {:>6} calls  p50 {:>7.2} ms  p99 {:>7.2} ms  max {:>7.2} ms",
            ms.len(),
            percentile(&ms, 0.5),
            percentile(&ms, 0.99),
            ms.last().copied().unwrap_or(f64::NAN)
        );
    }
    println!(
        "done {} of {submissions}; error responses {}; not done {}",
        stats.done,
        stats.errors.len(),
        stats.not_done.len()
    );
    for e in stats.errors.iter().chain(&stats.not_done).take(10) {
        println!("  {e}");
    }
    if stats.done != submissions || !stats.errors.is_empty() {
        std::process::exit(1);
    }
}
