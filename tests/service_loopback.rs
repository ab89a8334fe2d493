//! The zenoh shell end to end on loopback: a `contact serve` process on a free
//! port answers health, a good solve (identical to the library's answer) and a
//! bad request (structured error), and stays up.

use std::net::TcpListener;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use zenoh::Wait;

struct Server(Child);
impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port()
}

fn client(endpoint: &str) -> zenoh::Session {
    let mut c = zenoh::Config::default();
    c.insert_json5("mode", r#""client""#).unwrap();
    c.insert_json5("connect/endpoints", &format!(r#"["{endpoint}"]"#))
        .unwrap();
    c.insert_json5("scouting/multicast/enabled", "false").unwrap();
    c.insert_json5("scouting/gossip/enabled", "false").unwrap();
    zenoh::open(c).wait().expect("client session")
}

/// (ok?, payload) of the first reply.
fn query(s: &zenoh::Session, key: &str, payload: &[u8]) -> (bool, serde_json::Value) {
    let replies = s
        .get(key)
        .payload(payload.to_vec())
        .timeout(Duration::from_secs(60))
        .wait()
        .unwrap();
    let r = replies.recv().expect("a reply");
    match r.result() {
        Ok(sample) => (true, serde_json::from_slice(&sample.payload().to_bytes()).unwrap()),
        Err(err) => (false, serde_json::from_slice(&err.payload().to_bytes()).unwrap()),
    }
}

#[test]
fn serve_answers_over_loopback() {
    let endpoint = format!("tcp/127.0.0.1:{}", free_port());
    let _server = Server(
        Command::new(env!("CARGO_BIN_EXE_contact"))
            .args(["serve", "--listen", &endpoint])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap(),
    );
    // A client cannot open against a port nobody listens on yet: retry.
    let start = Instant::now();
    let session = loop {
        let mut c = zenoh::Config::default();
        c.insert_json5("mode", r#""client""#).unwrap();
        c.insert_json5("connect/endpoints", &format!(r#"["{endpoint}"]"#))
            .unwrap();
        c.insert_json5("scouting/multicast/enabled", "false").unwrap();
        if zenoh::open(c).wait().is_ok() {
            break client(&endpoint);
        }
        assert!(start.elapsed() < Duration::from_secs(30), "service did not come up");
        std::thread::sleep(Duration::from_millis(100));
    };
    let (ok, health) = query(&session, "contact/health", b"");
    assert!(ok);
    assert_eq!(health["protocol"], "1");

    let path = format!(
        "{}/proto/examples/signorini_inline_block_on_vee.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let body = std::fs::read(&path).unwrap();
    let (ok, reply) = query(&session, "contact/solve", &body);
    assert!(ok, "{reply}");
    let direct = contact::solve_bytes(&body, &Default::default()).unwrap();
    assert_eq!(reply["status"], "solved");
    for (a, b) in reply["pairs"][0]["points"]
        .as_array()
        .unwrap()
        .iter()
        .zip(&direct.pairs[0].points)
    {
        assert_eq!(
            a["pressure"].as_f64().unwrap(),
            b.pressure,
            "zenoh and library answers differ"
        );
    }

    let (ok, err) = query(&session, "contact/solve", b"{not json");
    assert!(!ok);
    assert_eq!(err["code"], "malformed_json");
    let (ok, health) = query(&session, "contact/health", b"");
    assert!(ok);
    assert_eq!(health["solves_served"], 1);
    assert_eq!(health["errors_served"], 1);
}
