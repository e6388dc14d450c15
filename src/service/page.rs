//! The web page at `/`: upload a file, the job list with live progress bars, and for a
//! finished job its surface mesh in 3-D coloured by face marker, the marker list and the
//! radius-ratio histogram. One HTML file with its own small WebGL viewer (flat-shaded
//! triangles, mouse to turn and zoom), built into the binary: no viewer library to vendor and
//! keep current for what is one draw call, and nothing to fetch at run time. It uses only the
//! public API (`/v1/jobs`, `/v1/jobs/{id}/surface`), with the bearer token typed into it.

use axum::http::header;
use axum::response::IntoResponse;

const PAGE: &str = include_str!("page.html");

pub async fn index() -> impl IntoResponse {
    (
        [
            (header::CONTENT_TYPE, "text/html; charset=utf-8"),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        PAGE,
    )
}
