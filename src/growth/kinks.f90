!> The kinks of one growth step (docs/theory/growth.md#the-growth-step): each growing tip as the
!> growth criterion turns it (ddc_growth_criterion: its K, predictor angle and increment in; its
!> applied angle, reason, solves and link out), the step's links, the last trial geometry
!> solved, and the model grown at the applied angles.
module ddc_growth_kinks
    use ddc_kinds, only: wp
    use ddc_model_types, only: model_type, growth_options
    use ddc_model_results, only: model_results, growth_grew, growth_corrector_failed
    use ddc_growth_extension, only: tip_path, make_path, extend_model, element_split
    use ddc_growth_clearance, only: tip_link, link_parts, ends_on_link
    use ddc_model_trial_records, only: trial_records
    implicit none
    private

    public :: kink, step_kinks, kink_path, step_links, grow_paths

    !> A growing tip of the step as the growth criterion turns it.
    type :: kink
        !> Fracture (1-based) and end (tip_end_begin, tip_end_end) of the tip, and its index
        !> among the run's growing tips
        integer :: fracture = 0, end = 0, tip = 0
        !> K_I, K_II and K_eq of the tip before growing [stress unit * length unit**0.5]
        real(wp) :: k1 = 0.0_wp, k2 = 0.0_wp, k_eq = 0.0_wp
        !> The criterion's kink angle from the tip's K (the predictor, the MTS angle) [rad]
        real(wp) :: theta_predictor = 0.0_wp
        !> Length of the kink [length unit] and its number of elements: the increment, or
        !> shorter where the criterion shortens the kink
        real(wp) :: length = 0.0_wp
        integer :: pieces = 1
        !> Length of the increment, and of its elements [length unit]
        real(wp) :: full_length = 0.0_wp, element_length = 0.0_wp
        !> The length the local-symmetry corrector tries first: twice the tip's last kink, at
        !> most the increment [length unit]; 0: the increment
        real(wp) :: first_length = 0.0_wp
        !> The applied angle [rad] (out)
        real(wp) :: theta = 0.0_wp
        !> Solves this tip took part in (out)
        integer :: solves = 0
        !> The work criterion's efficiency at the applied angle [stress unit * length unit]
        !> (out; 0 under another criterion)
        real(wp) :: efficiency = 0.0_wp
        !> The share of that trial's work change done through slip of frictional faces, new and
        !> old [-] (out; NaN without a candidate, 0 under another criterion)
        real(wp) :: slip_share = 0.0_wp
        !> growth_grew, growth_corrector_failed, growth_intersection, growth_surface (broke
        !> through the free surface), growth_linked, growth_closed or growth_enclosing (out)
        integer :: reason = growth_grew
        !> The link of a tip that linked or broke through the surface (out)
        type(tip_link) :: link
    end type kink

    !> One step's kinks: the growing tips, the step's links made before, and the last
    !> trial geometry the criterion solved (grown from the base: the model before growing).
    type :: step_kinks
        !> The growth step
        integer :: step = 0
        !> The growing tips
        type(kink), allocatable :: tip(:)
        !> The step's links made before the kinks are turned (tips that link at their
        !> predictor angle)
        type(tip_link), allocatable :: fixed(:)
        !> The last model grown (without observations) and the step that created each of its
        !> elements, shape (trial n) (out)
        type(model_type) :: trial
        integer, allocatable :: trial_created(:)
        !> The element of the base each element of trial comes from (0: new), shape
        !> (trial n), and the index in trial of each element of the base (0: split), shape
        !> (base n) (out)
        integer, allocatable :: origin(:), moved_to(:)
        !> The trial's solution (out)
        type(model_results) :: solved
        !> trial and solved are the base grown at the applied angles (out); otherwise that
        !> model is still to be built (grow_paths) and solved
        logical :: current = .false.
        !> The work criterion's trials of the step (out; not allocated under another)
        type(trial_records) :: trials
    end type step_kinks

contains

    !> The path of a kink at its applied angle.
    pure function kink_path(model, k) result(path)
        !> The model before growing
        type(model_type), intent(in) :: model
        !> The kink
        type(kink), intent(in) :: k
        type(tip_path) :: path

        path = make_path(model, k%fracture, k%end, k%theta, k%length, k%pieces)
    end function kink_path

    !> The step's links so far: those made before, then the kinks'.
    pure function step_links(kinks) result(made)
        !> The step's kinks
        type(step_kinks), intent(in) :: kinks
        type(tip_link), allocatable :: made(:)
        integer :: i

        made = kinks%fixed
        do i = 1, size(kinks%tip)
            if (ends_on_link(kinks%tip(i)%reason)) made = [made, kinks%tip(i)%link]
        end do
    end function step_links

    !> The model grown at the kinks' applied angles (those that grew or fell back to their
    !> predictor angle) and with the step's links: kinks%trial, trial_created, moved_to and
    !> origin (kinks%solved is left to the caller's solve).
    subroutine grow_paths(model, created, options, kinks)
        !> The model before growing
        type(model_type), intent(in) :: model
        !> Growth step that created each element of model, shape (n)
        integer, intent(in) :: created(:)
        !> Growth options (new_mu, new_sf)
        type(growth_options), intent(in) :: options
        !> The step's kinks, with their applied angles and reasons
        type(step_kinks), intent(inout) :: kinks
        type(tip_path), allocatable :: paths(:), link_paths(:)
        type(element_split), allocatable :: splits(:)
        logical :: grows(size(kinks%tip))
        integer :: i, m

        call link_parts(step_links(kinks), link_paths, splits)
        grows = kinks%tip%reason == growth_grew .or. kinks%tip%reason == growth_corrector_failed
        ! Filled in place: array constructors of a type with allocatable components leak
        ! their temporaries with gfortran (valgrind).
        allocate (paths(count(grows) + size(link_paths)))
        m = 0
        do i = 1, size(kinks%tip)
            if (.not. grows(i)) cycle
            m = m + 1
            paths(m) = kink_path(model, kinks%tip(i))
        end do
        paths(m + 1:) = link_paths
        call extend_model(model, created, paths, kinks%step, options, kinks%trial, &
                          kinks%trial_created, kinks%moved_to, splits, kinks%origin)
    end subroutine grow_paths

end module ddc_growth_kinks
