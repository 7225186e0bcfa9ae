//! A live viewer as a sink that can never stall a run or its file. Rerun's gRPC sink blocks
//! its sender while a viewer that accepted the connection does not read; in one recording
//! stream with the file sink, that stalls the file too, and the stream's shutdown waits for
//! it for ever. Here messages go to the gRPC sink through a bounded queue on a thread of its
//! own: a viewer that falls [`QUEUE`] messages behind loses the rest (counted and reported
//! when the run flushes), and a flush waits at most its timeout. The thread is never joined,
//! so a viewer stuck for good cannot keep the process from ending.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, SyncSender, TrySendError, sync_channel};
use std::time::{Duration, Instant};

use rerun::log::{ChunkBatcherConfig, LogMsg};
use rerun::sink::{GrpcSink, GrpcSinkConnectionState, LogSink, SinkFlushError};

/// Messages held for a viewer that reads slower than the run logs.
const QUEUE: usize = 4096;

/// What the forwarding thread is asked to do.
enum Request {
    Send(LogMsg),
    /// Flush the gRPC sink within the timeout and answer.
    Flush(Duration, SyncSender<Result<(), SinkFlushError>>),
}

/// A [`GrpcSink`] behind a bounded queue (module docs).
pub struct DetachedViewer {
    url: String,
    requests: SyncSender<Request>,
    dropped: Arc<AtomicU64>,
    /// Set once a flush found the viewer stalled: later messages are dropped at once and later
    /// flushes fail at once, so that one stalled viewer costs one [`FLUSH_WAIT`] in all.
    stalled: AtomicBool,
}

/// The longest a flush waits for the viewer (the run's own flush may wait longer for its file).
const FLUSH_WAIT: Duration = Duration::from_secs(5);

impl DetachedViewer {
    /// Waits until the viewer at `url` answers the connection of `grpc` (at most
    /// [`ANSWER_WAIT`]), then forwards to it from a thread of its own.
    pub fn connect(grpc: GrpcSink, url: &str) -> Result<Self, String> {
        connected(&grpc, ANSWER_WAIT).map_err(|e| format!("--connect {url}: {e}"))?;
        let (requests, incoming) = sync_channel(QUEUE);
        std::thread::Builder::new()
            .name("slipfront-viewer".into())
            .spawn(move || forward(&grpc, &incoming))
            .map_err(|e| format!("cannot start the viewer connection: {e}"))?;
        Ok(Self {
            url: url.to_string(),
            requests,
            dropped: Arc::new(AtomicU64::new(0)),
            stalled: AtomicBool::new(false),
        })
    }
}

/// Hands every request to `grpc`, in order, until the sender is gone.
fn forward(grpc: &GrpcSink, incoming: &Receiver<Request>) {
    while let Ok(request) = incoming.recv() {
        match request {
            Request::Send(message) => grpc.send(message),
            Request::Flush(timeout, answer) => {
                let _ = answer.send(grpc.flush_blocking(timeout));
            }
        }
    }
}

/// Whether a Rerun viewer (a gRPC server, HTTP/2 without TLS) answers at `address`: the TCP
/// connection is made within 2 s, and the server's first frame, its SETTINGS, arrives within
/// [`ANSWER_WAIT`] of the client's connection preface (RFC 9113 §3.4). Rerun's gRPC sink
/// reports itself connected as soon as TCP is, so an endpoint that accepts connections and
/// never speaks would otherwise take the whole run and show nothing.
pub fn answers(address: &str) -> Result<(), String> {
    use std::io::{Read, Write};
    use std::net::{TcpStream, ToSocketAddrs};
    const PREFACE: &[u8] = b"PRI * HTTP/2.0\r\n\r\nSM\r\n\r\n";
    /// An empty SETTINGS frame: length 0, type 4, no flags, stream 0.
    const SETTINGS: [u8; 9] = [0, 0, 0, 4, 0, 0, 0, 0, 0];
    let addrs = address.to_socket_addrs().map_err(|e| format!("cannot resolve {address}: {e}"))?;
    let mut stream = addrs
        .filter_map(|a| TcpStream::connect_timeout(&a, Duration::from_secs(2)).ok())
        .next()
        .ok_or_else(|| "no Rerun viewer is listening there".to_string())?;
    let silent = || {
        format!(
            "the endpoint accepted the connection but did not answer as a Rerun viewer (no HTTP/2 settings within {} s)",
            ANSWER_WAIT.as_secs()
        )
    };
    stream.set_read_timeout(Some(ANSWER_WAIT)).map_err(|e| e.to_string())?;
    stream.set_write_timeout(Some(ANSWER_WAIT)).map_err(|e| e.to_string())?;
    stream.write_all(PREFACE).and_then(|()| stream.write_all(&SETTINGS)).map_err(|_| silent())?;
    let mut header = [0u8; 9];
    stream.read_exact(&mut header).map_err(|_| silent())?;
    // The frame type is the header's fourth byte: the server's first frame must be SETTINGS.
    if header[3] == 4 { Ok(()) } else { Err(silent()) }
}

/// How long a viewer that accepted the connection may take to answer it.
const ANSWER_WAIT: Duration = Duration::from_secs(5);

/// Waits at most `wait` until the viewer has answered the connection: an endpoint that
/// accepts TCP connections but never speaks is refused before the run starts.
fn connected(grpc: &GrpcSink, wait: Duration) -> Result<(), String> {
    let deadline = Instant::now() + wait;
    loop {
        match grpc.status() {
            GrpcSinkConnectionState::Connected | GrpcSinkConnectionState::Disconnected(Ok(())) => return Ok(()),
            GrpcSinkConnectionState::Disconnected(Err(e)) => return Err(format!("the connection failed: {e}")),
            GrpcSinkConnectionState::Connecting { .. } if Instant::now() >= deadline => {
                return Err(format!(
                    "the endpoint accepted the connection but did not answer as a Rerun viewer within {} s",
                    wait.as_secs()
                ));
            }
            GrpcSinkConnectionState::Connecting { .. } => std::thread::sleep(Duration::from_millis(20)),
        }
    }
}

impl LogSink for DetachedViewer {
    fn send(&self, message: LogMsg) {
        if self.stalled.load(Ordering::Relaxed)
            || matches!(
                self.requests.try_send(Request::Send(message)),
                Err(TrySendError::Full(_) | TrySendError::Disconnected(_))
            )
        {
            self.dropped.fetch_add(1, Ordering::Relaxed);
        }
    }

    fn flush_blocking(&self, timeout: Duration) -> Result<(), SinkFlushError> {
        let stalled = || {
            SinkFlushError::failed(format!(
                "the viewer at {} stopped reading ({} messages were not shown to it); the files are complete",
                self.url,
                self.dropped.load(Ordering::Relaxed)
            ))
        };
        if self.stalled.load(Ordering::Relaxed) {
            return Err(stalled());
        }
        let timeout = timeout.min(FLUSH_WAIT);
        let (answer, answered) = sync_channel(1);
        if self.requests.try_send(Request::Flush(timeout, answer)).is_err() {
            self.stalled.store(true, Ordering::Relaxed);
            return Err(stalled());
        }
        let result = answered.recv_timeout(timeout);
        if !matches!(result, Ok(Ok(()))) {
            self.stalled.store(true, Ordering::Relaxed);
        }
        match result {
            Ok(Ok(())) if self.dropped.load(Ordering::Relaxed) == 0 => Ok(()),
            Ok(Ok(())) => Err(stalled()),
            Ok(Err(e)) => Err(SinkFlushError::failed(format!("{e} ({}); the files are complete", self.url))),
            Err(_) => Err(stalled()),
        }
    }

    fn default_batcher_config(&self) -> ChunkBatcherConfig {
        // As the gRPC sink's own: viewers are live streams.
        ChunkBatcherConfig::LOW_LATENCY
    }
}
