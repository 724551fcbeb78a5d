!> States of a contact element (docs/theory/contact.md#the-contact-law-of-one-element): the codes
!> every solver and output share.
module ddc_contact_states
    implicit none
    private

    !> Closed without slip; closed on the friction limit; open (S_n' = 0)
    integer, parameter, public :: state_stick = 1, state_slip = 2, state_open = 3

end module ddc_contact_states
