use ratatui::{Terminal, backend::TestBackend};
use raystep::tui::{self, App};

#[test]
fn scratch() {
    let mut app = App::open(None, true).unwrap();
    let mut terminal = Terminal::new(TestBackend::new(120, 40)).unwrap();
    tui::draw(&mut terminal, &mut app).unwrap();
    println!("{}", terminal.backend());
}
