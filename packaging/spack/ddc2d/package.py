# Spack package of ddc2d (docs/install.md#spack). Copy this folder into the packages/
# folder of a Spack repository of your own (`spack repo create`) and build it; the
# variants map to the options of CMakeLists.txt (tests/install/test_install.py checks that
# the names agree).
# Written for Spack 1.x (build systems in the builtin repository). Spack's package
# language comes from its star import: ruff cannot see its names.
# ruff: noqa: F403, F405
from spack.package import *
from spack_repo.builtin.build_systems.cmake import CMakePackage, generator


class Ddc2d(CMakePackage):
    """2D displacement discontinuity method with frictional contact for faults and
    fractures: the program ddc2d, a Fortran library (find_package(ddc2d)) and an Lmod
    module file."""

    # ddc2d's own sources; hmat-oss (+hmatrix) is GPL-2.0-or-later, and a program linked
    # with it is distributed under the GPL's terms (README.md#licence).
    license("MIT")

    # ddc2d has no public release address yet: from the root of a checkout, build it with
    # `spack dev-build ddc2d@0.1.0` (or `spack develop`); set `git` (and a
    # version("main", branch="main")) to your copy of the repository to fetch it instead.
    # The newest version is project(VERSION) of CMakeLists.txt (the test package_metadata).
    version("0.1.0")

    variant("mpi", default=False, description="One model over many processes (MPI, ScaLAPACK)")
    variant("native", default=False, description="Optimise for the building CPU (-march=native)")
    variant("hmatrix", default=True,
            description="Hierarchical matrices with hmat-oss (GPL-2.0-or-later)")

    depends_on("cmake@3.25:", type="build")
    depends_on("ninja", type="build")
    depends_on("fortran", type="build")
    depends_on("c", type="build")
    depends_on("blas")
    depends_on("lapack")
    # Serial HDF5 in the MPI build too: one process writes the result file.
    depends_on("hdf5+fortran~mpi")
    depends_on("hmat-oss", when="+hmatrix")
    depends_on("mpi", when="+mpi")
    depends_on("scalapack", when="+mpi")

    generator("ninja")

    def cmake_args(self):
        args = [
            self.define_from_variant("DDC2D_MPI", "mpi"),
            self.define_from_variant("DDC2D_NATIVE", "native"),
            self.define_from_variant("DDC2D_HMATRIX", "hmatrix"),
            # The tests need pFUnit and a Python venv: not part of an installation.
            self.define("BUILD_TESTING", False),
        ]
        if self.spec.satisfies("+mpi"):
            # CMakeLists.txt looks ScaLAPACK up by name: give it Spack's.
            args.append(self.define("SCALAPACK_LIBRARY",
                                    self.spec["scalapack"].libs.joined(";")))
        return args
