!> A crack of half-length a = 1 m opened by a fluid pressure p = 10 MPa, built in code and
!> solved with the ddc2d library; prints K_I at both tips against the closed form
!> p sqrt(pi a) and exits 1 when one differs by more than 1 %.
program pressurized_crack
    use ddc_api_library, only: wp, error_type, ddc_model, ddc_result, new_model, &
        add_fracture, solve, get_tips
    implicit none

    real(wp), parameter :: pi = acos(-1.0_wp), a = 1.0_wp, p = 10.0_wp, tolerance = 0.01_wp
    type(ddc_model) :: model
    type(ddc_result) :: result
    type(error_type), allocatable :: error
    real(wp), allocatable :: k1(:), x(:)
    real(wp) :: exact
    integer :: i

    call new_model(model, youngs_modulus=50000.0_wp, poissons_ratio=0.25_wp, error=error)
    if (allocated(error)) call fail(error)
    ! 'traction': the total normal traction on the faces is -p (tension positive).
    call add_fracture(model, x=[-a, a], y=[0.0_wp, 0.0_wp], counts=[200], error=error, &
                      condition='traction', bc_s=0.0_wp, bc_n=-p, name='crack')
    if (allocated(error)) call fail(error)
    call solve(model, result, error)
    if (allocated(error)) call fail(error)

    call get_tips(result, k1=k1, x=x)
    exact = p * sqrt(pi * a)
    do i = 1, size(k1)
        write (*, '(a, f7.3, a, f9.4, a, f9.4, a, es9.2)') 'tip x = ', x(i), ': K_I = ', &
            k1(i), ' MPa m^1/2, closed form ', exact, ', relative error ', &
            abs(k1(i) - exact) / exact
    end do
    if (size(k1) /= 2 .or. any(abs(k1 - exact) > tolerance * exact)) then
        write (*, '(a)') 'K_I differs from the closed form by more than 1 %'
        stop 1
    end if

contains

    !> Print the library's message and stop with its exit code.
    subroutine fail(error)
        type(error_type), intent(in) :: error

        write (*, '(a)') 'ddc2d: '//error%message
        error stop error%code
    end subroutine fail

end program pressurized_crack
