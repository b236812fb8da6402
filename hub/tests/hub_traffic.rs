mod common;
use canstar_hub::hub::HubConfig;
use common::*;

#[test]
fn smoke() {
    let cfg = HubConfig { sublinks: 0, ..Default::default() };
    let mut nodes = vec![Node::default(), Node::default(), Node::default()];
    nodes[0].queue.push_back(Frame::std(0x123, &[1, 2, 3]));
    let mut net = Net::new(&cfg, nodes);
    net.run_until_idle(400);
    println!("{}", net.trace(0));
    assert_eq!(net.frames_ok(), 1);
    assert_eq!(net.errors(), 0);
}
