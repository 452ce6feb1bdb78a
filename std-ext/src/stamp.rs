//! When and where a measurement was made, for every recorded run the book
//! and the reports show: timings mean little without the machine.

/// `YYYY-MM-DD HH:MM UTC · CPU model, N cores`, from the system clock and
/// (on Linux) `/proc/cpuinfo`.
///
/// ```
/// let stamp = bvhkit_std::stamp::now();
/// assert!(stamp.contains(" UTC · ") && stamp.ends_with(" cores"));
/// ```
pub fn now() -> String {
    let t = time::OffsetDateTime::now_utc();
    format!(
        "{:04}-{:02}-{:02} {:02}:{:02} UTC · {}",
        t.year(),
        u8::from(t.month()),
        t.day(),
        t.hour(),
        t.minute(),
        machine()
    )
}

/// The CPU model (the architecture where it cannot be read) and the cores
/// this process may use.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{cpu}, {cores} cores")
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_stamp_has_the_date_time_and_machine() {
        let s = super::now();
        let (date, rest) = s.split_once(" UTC · ").expect("date · machine");
        assert_eq!(date.len(), "2026-11-26 06:20".len(), "{s}");
        assert!(date.starts_with("20") && date.as_bytes()[4] == b'-', "{s}");
        assert!(rest.ends_with(" cores"), "{s}");
    }
}
