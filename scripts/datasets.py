"""Shared by the oracle checks: where the binary and the oracles are, and the datasets found."""
import glob, json, os

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
ORACLE = os.path.join(ROOT, '..', 'shared', 'datasets', 'oracle')
BIN = os.path.join(ROOT, 'target', 'release', 'starplex')


def with_oracles(data, sizes):
    """Yields (size, name, spx path, oracle dict) for every DATA/SIZE/*/*.spx that has an oracle;
    prints a line for each that has none."""
    for size in sizes:
        for spx in sorted(glob.glob(os.path.join(data, size, '*', '*.spx'))):
            name = os.path.basename(spx)[:-4]
            o_path = os.path.join(ORACLE, name + '.json')
            if not os.path.exists(o_path):
                print('%-20s no oracle' % name)
                continue
            with open(o_path) as f:
                yield size, name, spx, json.load(f)
