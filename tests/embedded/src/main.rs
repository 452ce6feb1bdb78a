//! bvhkit on a Cortex-M4: builds BVHs over two small objects from `static`
//! buffers, runs two-tree and ray queries, and prints the answers, the cycle
//! counts and the stack high-water mark through semihosting. The host check
//! (`scripts/embedded-demo`) compares every answer line with brute force.
//!
//! Output lines (`key value...`), one per fact:
//! `pairs <label> <count> <digest>`, `exact <label> <count> <digest>`,
//! `ray <label> <r> <prim|none> <t bits>`, `cycles <what> <n>`, `stack <bytes>`.
#![no_std]
#![no_main]
// The baseline build (no feature) leaves the scene and the clock unused.
#![cfg_attr(
    not(any(feature = "minimal", feature = "boxes", feature = "baked")),
    allow(dead_code)
)]

// The boxes set uses only the moving boxes of the scene.
#[cfg_attr(not(any(feature = "minimal", feature = "baked")), allow(dead_code))]
mod scene;

use core::ptr::addr_of_mut;
use core::sync::atomic::{AtomicU32, Ordering};

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m_rt::{entry, exception};
use cortex_m_semihosting::{debug, hprintln};

#[cfg(feature = "minimal")]
use bvhkit::{max_nodes, Aabb, Node, Triangle};
#[cfg(feature = "minimal")]
use scene::N;

/// Every buffer the demo uses, in `.bss`: nothing on the heap, little on the stack.
#[cfg(feature = "minimal")]
mod buffers {
    use super::*;
    pub static mut TRIS_A: [Triangle; N] = [Triangle::new(
        bvhkit::glam::Vec3::ZERO,
        bvhkit::glam::Vec3::ZERO,
        bvhkit::glam::Vec3::ZERO,
    ); N];
    pub static mut TRIS_B: [Triangle; N] = [Triangle::new(
        bvhkit::glam::Vec3::ZERO,
        bvhkit::glam::Vec3::ZERO,
        bvhkit::glam::Vec3::ZERO,
    ); N];
    /// Zero bits go to `.bss`; `init-empty` measures what `Node::EMPTY`
    /// (infinite bounds: initialised data, stored in flash) costs instead.
    #[cfg(not(feature = "init-empty"))]
    const INIT: Node<Aabb> = Node::ZERO;
    #[cfg(feature = "init-empty")]
    const INIT: Node<Aabb> = Node::EMPTY;
    pub static mut NODES_A: [Node<Aabb>; max_nodes(N)] = [INIT; max_nodes(N)];
    pub static mut NODES_B: [Node<Aabb>; max_nodes(N)] = [INIT; max_nodes(N)];
    pub static mut INDEX_A: [u32; N] = [0; N];
    pub static mut INDEX_B: [u32; N] = [0; N];
}

// ---- timing: the DWT cycle counter when the core has one, else SysTick ----

static SYSTICK_WRAPS: AtomicU32 = AtomicU32::new(0);
const RELOAD: u32 = 0x00FF_FFFF;

#[exception]
fn SysTick() {
    SYSTICK_WRAPS.fetch_add(1, Ordering::Relaxed);
}

struct Clock {
    dwt: bool,
}

impl Clock {
    /// Ticks, modulo 2^32: a step's count is the wrapping difference of
    /// two readings (right for any step under 2^32 ticks), and printing a
    /// `u32` links no 64-bit division, which the footprint table would
    /// otherwise charge to every feature set but the baseline (1.1 KB).
    fn now(&self) -> u32 {
        if self.dwt {
            return cortex_m::peripheral::DWT::cycle_count();
        }
        // SysTick counts down from RELOAD; wraps are counted by the handler.
        loop {
            let w = SYSTICK_WRAPS.load(Ordering::Acquire);
            let v = cortex_m::peripheral::SYST::get_current();
            if SYSTICK_WRAPS.load(Ordering::Acquire) == w {
                return w.wrapping_mul(RELOAD + 1).wrapping_add(RELOAD - v);
            }
        }
    }

    /// Runs `f`, printing its tick count and its stack high-water mark.
    fn time<T>(&self, what: &str, f: impl FnOnce() -> T) -> T {
        paint_stack();
        let start = self.now();
        let out = f();
        let end = self.now();
        let stack = stack_high_water();
        hprintln!("cycles {} {}", what, end.wrapping_sub(start));
        hprintln!("stack {} {}", what, stack);
        out
    }
}

// ---- stack high-water mark: paint the free stack, scan after the work ----

const PAINT: u32 = 0xC0FF_EE11;

extern "C" {
    static mut __sheap: u32;
    static _stack_start: u32;
}

/// Fills the unused stack (from the end of `.bss` to a little below the
/// current stack pointer) with a pattern.
fn paint_stack() {
    let bottom = addr_of_mut!(__sheap) as usize;
    let sp = cortex_m::register::msp::read() as usize;
    let mut p = bottom;
    while p + 256 < sp {
        // SAFETY: [bottom, sp - 256) is RAM no live object uses: above it is
        // this frame, below it `.bss`.
        unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
        p += 4;
    }
}

/// Bytes of stack ever used: from the top down to the lowest overwritten word.
fn stack_high_water() -> usize {
    let bottom = addr_of_mut!(__sheap) as usize;
    let top = core::ptr::addr_of!(_stack_start) as usize;
    let mut p = bottom;
    // SAFETY: reads of painted, otherwise unused RAM.
    while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
        p += 4;
    }
    top - p
}

#[entry]
fn main() -> ! {
    let mut cp = cortex_m::Peripherals::take().unwrap();
    cp.DCB.enable_trace();
    cp.DWT.enable_cycle_counter();
    let dwt = {
        let a = cortex_m::peripheral::DWT::cycle_count();
        cortex_m::asm::delay(100);
        cortex_m::peripheral::DWT::cycle_count() != a
    };
    if !dwt {
        cp.SYST.set_clock_source(SystClkSource::Core);
        cp.SYST.set_reload(RELOAD);
        cp.SYST.clear_current();
        cp.SYST.enable_interrupt();
        cp.SYST.enable_counter();
    }
    let clock = Clock { dwt };
    hprintln!("clock {}", if dwt { "dwt-cycles" } else { "systick" });
    paint_stack();
    let ok = run(&clock);
    hprintln!("stack all {}", stack_high_water());
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    loop {
        cortex_m::asm::wfi();
    }
}

/// A panic is a failed run: say so and exit with a failure code.
#[panic_handler]
fn panic(info: &core::panic::PanicInfo) -> ! {
    hprintln!("panic {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}

#[cfg(not(any(feature = "minimal", feature = "boxes", feature = "baked")))]
fn run(_clock: &Clock) -> bool {
    hprintln!("baseline: no bvhkit work");
    true
}

#[cfg(any(feature = "minimal", feature = "boxes", feature = "baked"))]
#[inline(never)]
fn run(clock: &Clock) -> bool {
    #[cfg(feature = "minimal")]
    let done = demo(clock);
    #[cfg(all(feature = "boxes", not(feature = "minimal")))]
    let done = boxes::run(clock);
    #[cfg(all(feature = "baked", not(any(feature = "minimal", feature = "boxes"))))]
    let done = baked::run(clock);
    match done {
        Ok(()) => true,
        Err(e) => {
            print_error(e);
            false
        }
    }
}

/// Prints an error the way the feature set chooses, so that the footprint
/// table shows what each way costs: the fixed sentence by default (no
/// formatting code), `Display` or `Debug` with `print-display` or
/// `print-debug`.
#[cfg(any(feature = "minimal", feature = "boxes", feature = "baked"))]
#[inline(never)]
fn print_error(e: bvhkit::Error) {
    #[cfg(feature = "print-debug")]
    hprintln!("error {:?}", e);
    #[cfg(all(feature = "print-display", not(feature = "print-debug")))]
    hprintln!("error {}", e);
    #[cfg(feature = "print-float")]
    hprintln!(
        "error {} near {}",
        e.as_str(),
        core::hint::black_box(1.5f32)
    );
    #[cfg(not(any(
        feature = "print-debug",
        feature = "print-display",
        feature = "print-float"
    )))]
    hprintln!("error {}", e.as_str());
}

/// Pairs a query hands over at a time: they collect in a fixed `heapless`
/// buffer that is drained whenever it fills (as firmware forwarding contacts
/// in batches would), so a query reports any number of pairs in 64 bytes.
/// (32 pairs cost every step about 200 bytes more stack, since the demo's
/// frame holds the batch: measured with `scripts/book-measure embedded`.)
#[cfg(any(feature = "minimal", feature = "baked"))]
const PAIR_BATCH: usize = 8;

/// Times a pair query (`query` reports each pair to its callback), then
/// prints `kind label count digest`.
#[cfg(any(feature = "minimal", feature = "baked"))]
fn pairs(
    clock: &Clock,
    kind: &str,
    label: &str,
    query: impl FnOnce(&mut dyn FnMut(u32, u32)) -> Result<usize, bvhkit::Error>,
) -> Result<(), bvhkit::Error> {
    type Batch = heapless::Vec<(u32, u32), PAIR_BATCH>;
    fn drain(batch: &mut Batch, digest: &mut u32) {
        for &(i, j) in batch.iter() {
            *digest = digest.wrapping_add(scene::mix(i, j));
        }
        batch.clear();
    }
    let (mut batch, mut digest) = (Batch::new(), 0u32);
    let count = clock.time(label, || {
        query(&mut |i, j| {
            if batch.is_full() {
                drain(&mut batch, &mut digest);
            }
            let _ = batch.push((i, j)); // room: drained just above when full
        })
    })?;
    drain(&mut batch, &mut digest);
    hprintln!("{} {} {} {:08x}", kind, label, count, digest);
    Ok(())
}

/// Times the scene's rays on `tree` over object A, then prints each hit.
#[cfg(any(feature = "minimal", feature = "baked"))]
fn rays<H: bvhkit::Hierarchy>(
    clock: &Clock,
    label: &str,
    tree: &H,
    tris: &[bvhkit::Triangle],
    order: bvhkit::RayOrder,
) -> Result<(), bvhkit::Error> {
    use bvhkit::Query;
    let mut hits = heapless::Vec::<Option<bvhkit::Hit>, { scene::RAYS }>::new();
    clock.time(label, || -> Result<(), bvhkit::Error> {
        for r in 0..scene::RAYS {
            let (o, d) = scene::ray(r);
            let ray = bvhkit::Ray::new(o, d, f32::INFINITY)?;
            let _ = hits.push(tree.cast_ray(tris, &ray, order, ())?); // RAYS rays, room for RAYS
        }
        Ok(())
    })?;
    for (r, hit) in hits.iter().enumerate() {
        match hit {
            Some(h) => hprintln!("ray {} {} {} {:08x}", label, r, h.prim, h.t.to_bits()),
            None => hprintln!("ray {} {} none 0", label, r),
        }
    }
    Ok(())
}

#[cfg(feature = "minimal")]
#[inline(never)]
fn demo(clock: &Clock) -> Result<(), bvhkit::Error> {
    use buffers::*;
    use bvhkit::{Descent, RayOrder, SplitPoint, TopDown};

    // SAFETY: `demo` runs once; these are the only references to the buffers.
    let (tris_a, tris_b, nodes_a, nodes_b, index_a, index_b) = unsafe {
        (
            &mut *addr_of_mut!(TRIS_A),
            &mut *addr_of_mut!(TRIS_B),
            &mut *addr_of_mut!(NODES_A),
            &mut *addr_of_mut!(NODES_B),
            &mut *addr_of_mut!(INDEX_A),
            &mut *addr_of_mut!(INDEX_B),
        )
    };
    scene::object(0, tris_a);
    scene::object(1, tris_b);
    hprintln!("scene {} {}", N, N);
    let (tris_a, tris_b): (&[Triangle], &[Triangle]) = (tris_a, tris_b);

    // Eight bins: the SAH tree is nearly as good, and the builder's bin
    // array (and so its stack) half the size of the default sixteen.
    let sah = TopDown {
        split: SplitPoint::Bins(8),
        ..TopDown::sah()
    };
    let a = clock.time("build-sah-a", || sah.build(tris_a, nodes_a, index_a))?;
    let b = clock.time("build-sah-b", || sah.build(tris_b, nodes_b, index_b))?;
    hprintln!("tree a nodes {} depth {}", a.node_count(), a.depth());

    pairs(clock, "pairs", "aabb-sah-dfs", |f| {
        bvhkit::overlapping_pairs(&a, tris_a, &b, tris_b, Descent::Larger, f)
    })?;
    rays(clock, "aabb-dfs", &a, tris_a, RayOrder::DepthFirst)?;

    #[cfg(feature = "typical")]
    typical::run(clock, tris_a, tris_b, &a, &b)?;
    #[cfg(feature = "everything")]
    everything::run(clock, tris_a, tris_b, &a, &b)?;
    Ok(())
}

#[cfg(feature = "baked")]
mod baked;
#[cfg(feature = "boxes")]
mod boxes;
#[cfg(feature = "everything")]
mod everything;
#[cfg(feature = "typical")]
mod typical;
