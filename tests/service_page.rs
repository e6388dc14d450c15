//! The web page in a real browser: headless Chromium (Debian's `chromium`, installed by
//! `scripts/install-chromium.sh` from `make test`) driven over the DevTools protocol. It loads
//! `/`, puts a sample case into the upload field, submits, waits until the page has drawn the
//! finished job, and checks the screenshot of the canvas (a good part of it drawn in marker
//! colours) and the marker list (the job's markers, in order). Without Chromium the test says
//! so and skips, except under CI, where that is a failure.

mod common;

use base64::Engine;
use common::server::{root, scratch, Server};
use serde_json::{json, Value};
use std::io::{BufRead, BufReader};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};
use tungstenite::{Message, WebSocket};

fn chromium() -> Option<std::path::PathBuf> {
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join("chromium"))
            .find(|p| p.is_file())
    });
    if found.is_none() {
        assert!(
            std::env::var_os("CI").is_none(),
            "chromium missing (scripts/install-chromium.sh installs it; required when CI is set)"
        );
        println!("skipping: chromium not found (scripts/install-chromium.sh installs it)");
    }
    found
}

/// A headless Chromium; killed when dropped.
struct Browser {
    child: Child,
    port: u16,
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn launch(binary: &std::path::Path, profile: &std::path::Path) -> Browser {
    let mut child = Command::new(binary)
        .args([
            "--headless",
            "--no-sandbox",
            "--no-first-run",
            "--enable-unsafe-swiftshader",
            "--use-angle=swiftshader",
            "--window-size=1400,900",
            "--remote-debugging-address=127.0.0.1",
            "--remote-debugging-port=0",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg("about:blank")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starting chromium");
    // "DevTools listening on ws://127.0.0.1:PORT/devtools/browser/…" on stderr.
    let stderr = child.stderr.take().expect("stderr");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            if let Some(rest) = line.split("ws://127.0.0.1:").nth(1) {
                let port: String = rest.chars().take_while(char::is_ascii_digit).collect();
                let _ = tx.send(port.parse::<u16>().ok());
            }
        }
    });
    let port = rx
        .recv_timeout(Duration::from_secs(30))
        .ok()
        .flatten()
        .expect("chromium's DevTools port");
    Browser { child, port }
}

/// One DevTools connection to a page, with numbered calls.
struct Page {
    ws: WebSocket<TcpStream>,
    next: u64,
}

impl Page {
    fn open(browser: &Browser) -> Page {
        let list = ureq::get(&format!("http://127.0.0.1:{}/json/list", browser.port))
            .call()
            .expect("target list")
            .into_string()
            .unwrap();
        let targets: Value = serde_json::from_str(&list).unwrap();
        let url = targets
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["type"] == "page")
            .and_then(|t| t["webSocketDebuggerUrl"].as_str())
            .expect("a page target")
            .to_string();
        let stream = TcpStream::connect(("127.0.0.1", browser.port)).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_secs(60)))
            .unwrap();
        let (ws, _) = tungstenite::client(url.as_str(), stream).expect("DevTools WebSocket");
        Page { ws, next: 1 }
    }

    fn call(&mut self, method: &str, params: Value) -> Value {
        let id = self.next;
        self.next += 1;
        let message = json!({ "id": id, "method": method, "params": params }).to_string();
        self.ws.send(Message::text(message)).expect("send");
        loop {
            let Message::Text(text) = self.ws.read().expect("read") else {
                continue;
            };
            let v: Value = serde_json::from_str(text.as_str()).unwrap();
            if v["id"] == id {
                assert!(v.get("error").is_none(), "{method}: {v}");
                return v["result"].clone();
            }
        }
    }

    /// A JavaScript expression's value (JSON-able).
    fn eval(&mut self, expression: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({ "expression": expression, "returnByValue": true, "awaitPromise": true }),
        );
        assert!(r.get("exceptionDetails").is_none(), "{expression}: {r}");
        r["result"]["value"].clone()
    }

    fn wait_for(&mut self, what: &str, expression: &str, limit: Duration) -> Value {
        let start = Instant::now();
        loop {
            let v = self.eval(expression);
            if v != Value::Null && v != Value::Bool(false) {
                return v;
            }
            assert!(start.elapsed() < limit, "timed out waiting for {what}");
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

#[test]
fn the_page_submits_a_sample_and_draws_its_surface_mesh() {
    let Some(binary) = chromium() else { return };
    let data = scratch("page");
    let server = Server::start(&data, &["--workers", "1", "--threads-per-job", "2"]);
    let browser = launch(&binary, &data.with_extension("chromium"));
    let mut page = Page::open(&browser);
    page.call("Page.enable", json!({}));
    page.call("Page.navigate", json!({ "url": server.url("/") }));
    page.wait_for(
        "the page",
        "document.readyState === 'complete' && !!window.tetrafoilView",
        Duration::from_secs(30),
    );

    // Put the sample into the file field and press Submit.
    let sample = root().join("samples/cube_cavity/case.toml");
    let document = page.call("DOM.getDocument", json!({}));
    let root_node = document["root"]["nodeId"].clone();
    let input = page.call(
        "DOM.querySelector",
        json!({ "nodeId": root_node, "selector": "#file" }),
    );
    page.call(
        "DOM.setFileInputFiles",
        json!({ "nodeId": input["nodeId"], "files": [sample.to_str().unwrap()] }),
    );
    page.eval("document.getElementById('send').click()");

    // The job list shows it, it finishes, the page draws it.
    let drawn = page.wait_for(
        "the drawn job",
        "window.tetrafoilView.drawn && window.tetrafoilView.shown",
        Duration::from_secs(90),
    );
    let id = drawn.as_str().expect("job id").to_string();
    let row = page.eval(&format!(
        "(() => {{ const r = document.querySelector('tr[data-id=\"{id}\"]');
                   return r && [r.dataset.state, r.querySelector('progress').value]; }})()"
    ));
    assert_eq!(row, json!(["done", 1]), "the job's row");
    let shown: Vec<String> = serde_json::from_value(
        page.eval("[...document.querySelectorAll('#markers li')].map(li => li.dataset.marker)"),
    )
    .unwrap();
    let job: Value = serde_json::from_str(
        &ureq::get(&server.url(&format!("/v1/jobs/{id}")))
            .call()
            .unwrap()
            .into_string()
            .unwrap(),
    )
    .unwrap();
    let markers: Vec<String> = serde_json::from_value(job["report"]["mesh"]["markers"].clone())
        .expect("the job's markers");
    assert_eq!(shown, markers, "the marker list is the job's");

    // The canvas's pixels: mostly background before, a good share drawn now.
    let rect = page.eval(
        "(() => { const r = document.getElementById('view').getBoundingClientRect();
                  return [r.x, r.y, r.width, r.height]; })()",
    );
    let [x, y, w, h]: [f64; 4] = serde_json::from_value(rect).unwrap();
    let shot = page.call(
        "Page.captureScreenshot",
        json!({ "format": "png",
                "clip": { "x": x, "y": y, "width": w, "height": h, "scale": 1 } }),
    );
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(shot["data"].as_str().expect("screenshot data"))
        .expect("base64");
    std::fs::write(data.with_extension("png"), &bytes).unwrap();
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().expect("PNG");
    let mut pixels = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut pixels).expect("PNG frame");
    let channels = info.color_type.samples();
    let background = [251i32, 252, 254];
    let (mut drawn, mut coloured, mut total) = (0usize, 0usize, 0usize);
    for px in pixels[..info.buffer_size()].chunks(channels) {
        total += 1;
        let rgb = [px[0] as i32, px[1] as i32, px[2] as i32];
        if rgb.iter().zip(background).any(|(a, b)| (a - b).abs() > 24) {
            drawn += 1;
            // Marker colours are saturated; the page's greys and border are not.
            let (lo, hi) = (*rgb.iter().min().unwrap(), *rgb.iter().max().unwrap());
            if hi - lo > 40 {
                coloured += 1;
            }
        }
    }
    assert!(
        drawn * 10 > total && coloured * 20 > total,
        "the canvas shows little of a mesh: {drawn} drawn, {coloured} in marker colours, of \
         {total} pixels"
    );
}
