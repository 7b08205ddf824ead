// Planted violation: using namespace std (declared here, since no std headers exist).
namespace std {  // expect: std-namespace
typedef unsigned size_type;
}

std::size_type count() { return 0; }  // expect: std-namespace
