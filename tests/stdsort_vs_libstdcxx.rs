//! Our replay of libstdc++'s introsort must give the same permutation as g++'s `std::sort` on inputs
//! with many ties: YADE's collider relies on it for the order of its first interactions. The test
//! compiles a small C++ program with the system g++ (the compiler Debian built YADE with is the same
//! libstdc++ family); it is skipped with a message when g++ is absent.
use ryade::stdsort::std_sort;
use std::io::Write;
use std::process::Command;

#[test]
fn permutation_equals_gxx_std_sort() {
    if Command::new("g++").arg("--version").output().is_err() {
        eprintln!("g++ not found: skipping the libstdc++ comparison");
        return;
    }
    let dir = std::env::temp_dir().join(format!("ryade-stdsort-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let src = dir.join("s.cpp");
    std::fs::File::create(&src)
        .unwrap()
        .write_all(
            br#"#include <algorithm>
#include <cstdio>
#include <vector>
struct E { int key; int idx; };
int main() {
  int n; std::vector<E> v;
  while (scanf("%d", &n) == 1) { v.clear(); for (int i = 0; i < n; i++) { int k; scanf("%d", &k); v.push_back({k, i}); }
    std::sort(v.begin(), v.end(), [](const E& a, const E& b) { return a.key < b.key; });
    for (auto& e : v) printf("%d ", e.idx); printf("\n"); }
}"#,
        )
        .unwrap();
    let exe = dir.join("s");
    let st = Command::new("g++")
        .args(["-O1", "-o"])
        .arg(&exe)
        .arg(&src)
        .status()
        .unwrap();
    assert!(st.success(), "g++ failed to compile the reference program");
    let mut seed = 12345u64;
    let mut input = String::new();
    let mut cases = Vec::new();
    for n in [3usize, 16, 17, 40, 100, 257, 1000, 4000] {
        for modulo in [2u64, 5, 50] {
            let keys: Vec<i64> = (0..n)
                .map(|_| {
                    seed = seed
                        .wrapping_mul(6364136223846793005)
                        .wrapping_add(1442695040888963407);
                    ((seed >> 33) % modulo) as i64
                })
                .collect();
            input.push_str(&format!("{} ", n));
            for k in &keys {
                input.push_str(&format!("{} ", k));
            }
            input.push('\n');
            cases.push(keys);
        }
    }
    let mut child = Command::new(&exe)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    for (keys, line) in cases.iter().zip(text.lines()) {
        let expect: Vec<usize> = line
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect();
        let mut ours: Vec<(i64, usize)> = keys.iter().copied().zip(0..).collect();
        std_sort(&mut ours, |a, b| a.0 < b.0);
        let got: Vec<usize> = ours.iter().map(|e| e.1).collect();
        assert_eq!(got, expect, "permutation differs for n={}", keys.len());
    }
    assert_eq!(text.lines().count(), cases.len());
}
