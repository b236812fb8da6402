#[test]
fn emit_tmp() {
    let mut u = canstar_controller::sja1000::Sja1000::new();
    canstar_hdl::drive::init(&mut u);
    std::fs::write("/tmp/sjav/top.v", canstar_hdl::flow::emit(&u)).unwrap();
}
