//! The processes a `compat` command starts stop with it.
//!
//! Every child (`compat run`, `yade`, `python -m yade.batch`) is started in a process group of its
//! own and registered here. On SIGINT, SIGTERM or SIGHUP the handler sends SIGTERM to every
//! registered group at once (a Ctrl-C in a terminal reaches only the foreground group, a `kill` or a
//! `timeout` only this process), no new child starts, and a watcher thread waits for the children to
//! end (up to `GRACE`, then SIGKILL), prints what the command kept (`set_kept`) and exits with
//! 128 + the signal. `python -m yade.batch` stops its own jobs (each in a session of its own) the
//! same way when it gets the SIGTERM.

use anyhow::{bail, Result};
use std::process::{Child, Command};
use std::sync::atomic::{AtomicI32, Ordering};
use std::sync::Mutex;
use std::time::{Duration, Instant};

const SLOTS: usize = 256;
/// Process group ids of the running children (0: free slot).
static GROUPS: [AtomicI32; SLOTS] = [const { AtomicI32::new(0) }; SLOTS];
/// The signal that stops this command (0: none yet).
static STOPPED: AtomicI32 = AtomicI32::new(0);
/// Write end of the pipe that wakes the watcher thread.
static WAKE: AtomicI32 = AtomicI32::new(-1);
/// How long the children get to end after the SIGTERM before they are killed.
const GRACE: Duration = Duration::from_secs(15);

type Kept = Box<dyn Fn() -> String + Send>;
static KEPT: Mutex<Option<Kept>> = Mutex::new(None);

extern "C" fn on_signal(sig: libc::c_int) {
    // async-signal-safe only: atomics, kill, write, _exit
    let first = STOPPED
        .compare_exchange(0, sig, Ordering::SeqCst, Ordering::SeqCst)
        .is_ok();
    let (to_children, exit_now) = if first {
        (libc::SIGTERM, false)
    } else {
        (libc::SIGKILL, true)
    };
    for g in GROUPS.iter() {
        let pg = g.load(Ordering::SeqCst);
        if pg > 0 {
            unsafe { libc::kill(-pg, to_children) };
        }
    }
    if exit_now {
        unsafe { libc::_exit(128 + sig) };
    }
    let fd = WAKE.load(Ordering::SeqCst);
    if fd >= 0 {
        let b = [sig as u8];
        unsafe { libc::write(fd, b.as_ptr() as *const libc::c_void, 1) };
    }
}

/// Install the handlers and the watcher (once, at the start of `main`).
pub fn install() {
    let mut fds = [0 as libc::c_int; 2];
    if unsafe { libc::pipe(fds.as_mut_ptr()) } != 0 {
        return;
    }
    WAKE.store(fds[1], Ordering::SeqCst);
    let rd = fds[0];
    std::thread::spawn(move || {
        let mut b = [0u8; 1];
        loop {
            let n = unsafe { libc::read(rd, b.as_mut_ptr() as *mut libc::c_void, 1) };
            if n == 1 {
                break;
            }
            if n == 0 {
                return;
            }
        }
        watcher();
    });
    for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
        unsafe {
            let mut sa: libc::sigaction = std::mem::zeroed();
            sa.sa_sigaction = on_signal as *const () as usize;
            libc::sigemptyset(&mut sa.sa_mask);
            libc::sigaction(sig, &sa, std::ptr::null_mut());
        }
    }
}

fn running() -> Vec<i32> {
    GROUPS
        .iter()
        .map(|g| g.load(Ordering::SeqCst))
        .filter(|&p| p > 0)
        .collect()
}

fn watcher() {
    let sig = STOPPED.load(Ordering::SeqCst);
    let name = match sig {
        libc::SIGINT => "SIGINT",
        libc::SIGTERM => "SIGTERM",
        libc::SIGHUP => "SIGHUP",
        _ => "a signal",
    };
    let n = running().len();
    eprintln!(
        "\ncompat: stopped by {}; stopping the {} process(es) it started",
        name, n
    );
    let t0 = Instant::now();
    // the command's threads wait for their children and unregister them
    while !running().is_empty() && t0.elapsed() < GRACE {
        std::thread::sleep(Duration::from_millis(50));
    }
    let left = running();
    for pg in &left {
        unsafe { libc::kill(-pg, libc::SIGKILL) };
    }
    if !left.is_empty() {
        eprintln!(
            "compat: killed {} process group(s) still running after {} s",
            left.len(),
            GRACE.as_secs()
        );
    }
    let kept = KEPT
        .lock()
        .ok()
        .and_then(|k| k.as_ref().map(|f| f()))
        .unwrap_or_default();
    if !kept.is_empty() {
        eprintln!("compat: {}", kept);
    }
    std::process::exit(128 + sig);
}

/// What the command keeps when it is stopped (e.g. the finished runs and how to resume), computed
/// when the signal comes.
pub fn set_kept(f: impl Fn() -> String + Send + 'static) {
    if let Ok(mut k) = KEPT.lock() {
        *k = Some(Box::new(f));
    }
}

/// When a signal is stopping the command, leave the exit (code 128 + signal, after the message of
/// what was kept) to the watcher; otherwise return at once.
pub fn wait_if_stopping() {
    if stopping() {
        loop {
            std::thread::sleep(Duration::from_secs(1));
        }
    }
}

/// Whether a signal is stopping the command.
pub fn stopping() -> bool {
    STOPPED.load(Ordering::SeqCst) != 0
}

/// A started child, unregistered when waited for or dropped.
pub struct Tracked {
    pub child: Child,
    slot: usize,
}

impl Tracked {
    pub fn wait(&mut self) -> std::io::Result<std::process::ExitStatus> {
        let r = self.child.wait();
        GROUPS[self.slot].store(0, Ordering::SeqCst);
        r
    }
}

impl Drop for Tracked {
    fn drop(&mut self) {
        GROUPS[self.slot].store(0, Ordering::SeqCst);
    }
}

/// Start `cmd` in a process group of its own, registered so that a signal stops it. Refused once
/// the command is stopping.
pub fn spawn(cmd: &mut Command) -> Result<Tracked> {
    use std::os::unix::process::CommandExt;
    if stopping() {
        bail!("not started: compat is stopping");
    }
    // its own group (a terminal's Ctrl-C reaches it through the handler); no terminal input, which a
    // background group could not read
    cmd.process_group(0).stdin(std::process::Stdio::null());
    let child = cmd.spawn()?;
    let pid = child.id() as i32;
    let slot = loop {
        if let Some(k) = GROUPS.iter().position(|g| {
            g.compare_exchange(0, pid, Ordering::SeqCst, Ordering::SeqCst)
                .is_ok()
        }) {
            break k;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    // a signal between the spawn and the registration missed this child
    if stopping() {
        unsafe { libc::kill(-pid, libc::SIGTERM) };
    }
    Ok(Tracked { child, slot })
}

/// `spawn` then wait: the exit status.
pub fn status(cmd: &mut Command) -> Result<std::process::ExitStatus> {
    let mut t = spawn(cmd)?;
    Ok(t.wait()?)
}

/// `spawn` with captured output, then wait: as `Command::output`.
pub fn output(cmd: &mut Command) -> Result<std::process::Output> {
    use std::io::Read;
    use std::process::Stdio;
    cmd.stdout(Stdio::piped()).stderr(Stdio::piped());
    let mut t = spawn(cmd)?;
    let mut so = t.child.stdout.take().unwrap();
    let mut se = t.child.stderr.take().unwrap();
    let h = std::thread::spawn(move || {
        let mut v = Vec::new();
        se.read_to_end(&mut v).ok();
        v
    });
    let mut stdout = Vec::new();
    so.read_to_end(&mut stdout)?;
    let stderr = h.join().unwrap_or_default();
    let status = t.wait()?;
    Ok(std::process::Output {
        status,
        stdout,
        stderr,
    })
}
