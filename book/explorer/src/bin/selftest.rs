//! The page's `?selftest` scenario run natively: prints the `key=value`
//! lines `scripts/test-book-in-browser` compares with the browser's.
fn main() {
    print!("{}", bvhkit_explorer::selftest());
}
