# Shared setup of the benchmarks against Pinocchio (sourced by bench/compare.sh and
# bench/symbolic_vs_pinocchio.sh, with ROOT set to the repository root):
#   - a throwaway venv .venv-bench (git-ignored) with pin, example-robot-data and the headers the
#     pin wheel's own headers need (cmeel-eigen, cmeel-urdfdom-headers);
#   - URDF[ur5], URDF[panda]: example-robot-data's files; OUT/<robot>.txt: their joint trees as
#     exported by Pinocchio's Python parser (bench/export_model.py);
#   - PINBENCH: bench/pinocchio_bench.cpp compiled against Pinocchio's headers (g++ -O3
#     -march=native -DNDEBUG), rebuilt when the source is newer.
VENV=$ROOT/.venv-bench
OUT=$ROOT/target/bench-compare
mkdir -p "$OUT"

if [ ! -x "$VENV/bin/python" ]; then
    python3 -m venv "$VENV"
fi
"$VENV/bin/pip" install -q pin example-robot-data cmeel-eigen cmeel-urdfdom-headers
SITE=$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
PREFIX=$SITE/cmeel.prefix
ROBOTS=$PREFIX/share/example-robot-data/robots
declare -A URDF=(
    [ur5]=$ROBOTS/ur_description/urdf/ur5_robot.urdf
    [panda]=$ROBOTS/panda_description/urdf/panda.urdf
)
for r in ur5 panda; do
    "$VENV/bin/python" bench/export_model.py "${URDF[$r]}" "$OUT/$r.txt"
done

CXXFLAGS="-std=c++17 -O3 -march=native -DNDEBUG"
PINBENCH=$OUT/pinocchio_bench
if [ ! -x "$PINBENCH" ] || [ bench/pinocchio_bench.cpp -nt "$PINBENCH" ]; then
    echo "compiling bench/pinocchio_bench.cpp (about two minutes) ..." >&2
    # The BOOST_* definitions are the ones Pinocchio's CMake config exports to its users.
    g++ $CXXFLAGS -w \
        -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
        -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
        -I"$PREFIX/include" -I"$PREFIX/include/eigen3" \
        bench/pinocchio_bench.cpp -o "$PINBENCH"
fi
